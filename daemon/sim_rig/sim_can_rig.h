#pragma once
// The CAN side of the one sim rig (docs/integrations.md): the simulated BMS bus with
// the SimBms on it, the simulated NMEA 2000 bus (when [can] n2k_interface
// is set: --sim puts it on this bus instead), and the daemon's CanService
// on the other end of both. With [engine] ecu = true a simulated engine ECU
// on the N2K bus sends 127488 from the plant's rpm every 0.1 s (rapid
// update), at source address 0; ecu = "silent" stops it. With [gps] a
// simulated GNSS receiver at source address 1 sends the position every
// second (129029 or 129025). The
// SimBms is driven by the plant's truth and tied to the plant's BMS
// disconnect: when it opens its contactor (its limits ignored for
// open_after_s) the plant's battery leaves the bus; a scenario's
// bms = "connect" closes it again. Everything runs on the loop's thread at
// the rig's deadlines, every CanService::kPollPeriodS of virtual time, so a
// run stays deterministic.
#include <functional>
#include <memory>
#include <ostream>
#include <string>

#include "canlink/can_service.h"
#include "config/settings.h"
#include "drivers/can/candump_recorder.h"
#include "drivers/can/sim_can_bus.h"
#include "drivers/sim/bms/sim_bms.h"
#include "drivers/sim/scenario.h"
#include "runtime/handoffs.h"

namespace xr::sim {

// The simulated buses' interface names (candump log lines, messages).
inline constexpr const char* kSimBmsInterface = "simcan0";
inline constexpr const char* kSimN2kInterface = "simcan1";

class SimCanRig {
 public:
  using Report = std::function<void(const std::string&)>;
  // `log` (may be null): --can-log, lines stamped in seconds since `start`.
  // `bmsBatteryTemp`: the BMS's 0x356 temperature is the battery
  // temperature input (the rig has no battery DS18B20 writing it).
  SimCanRig(const Scenario& scenario, const CanSettings& settings, rt::Handoffs& handoffs, TimeNs start,
            std::ostream* log, Report report, bool bmsBatteryTemp);

  // A scenario event's bms_* keys.
  void apply(const ScenarioEvent& e);
  // At a deadline: the BMS speaks (and may open its contactor), the service
  // reads. `now` is the loop clock's time.
  void step(TimeNs now, Plant& plant);

  const SimBms& bms() const { return bms_; }
  const canlink::CanService& service() const { return service_; }

 private:
  can::SimCanSegment bmsSegment_;
  can::SimCanNode& bmsNode_;  // the SimBms's controller
  can::SimCanNode& ourNode_;  // the daemon's controller
  can::SimCanSegment n2kSegment_;
  can::SimCanNode& ourN2kNode_;
  can::SimCanNode& ecuNode_;  // the simulated engine ECU ([engine] ecu = true)
  can::SimCanNode& gpsNode_;  // the simulated GNSS receiver ([gps])
  bool ecu_ = false, ecuTalking_ = true;
  TimeNs nextEcu_ = 0;
  ScenarioGps gps_;
  TimeNs nextGps_ = 0;
  std::uint8_t gpsSid_ = 0;
  SimBms bms_;
  bool simBms_ = false;
  std::unique_ptr<can::CandumpSink> sink_;
  canlink::CanService service_;
  TimeNs nextStep_ = 0;
  TimeNs start_ = 0;
  TimeNs now_ = 0;
};

}  // namespace xr::sim

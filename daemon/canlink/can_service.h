#pragma once
// CanService: the daemon's CAN side (docs/integrations.md), off the RT control thread.
// Each poll() drains the buses it was given and does what is due:
//   BMS bus : BmsCanLink decodes the configured protocol and posts each
//             change of the limits into Handoffs::bms, stamped with `now`
//             (the control loop's clock, so BmsStaleS is measured on it).
//   N2K bus : our NMEA 2000 node (n2k_node.h): address claim, heartbeat,
//             product information on request, status PGNs from telemetry.
// A bus that is missing or fails is retried with backoff (BusSlot) and
// never stops the regulator; meanwhile the limits go stale and the control
// law falls back to BmsFallbackCapA.
// What goes wrong on the buses (bad BMS frames, error frames, a bus that
// cannot be opened) becomes rate-limited events in Handoffs::sideEvents,
// which the EventPump delivers with the control thread's events.
//
// Who calls poll(): on a board, the xr-can thread every 10 ms
// (daemon/app/can_wiring); in simulation, the one sim rig at its deadlines
// on the loop's thread, like the DS18B20 read, so a run stays deterministic.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "can/bms_codec.h"
#include "canlink/bms_can_link.h"
#include "canlink/bus_slot.h"
#include "canlink/n2k_node.h"
#include "canlink/report_gate.h"
#include "drivers/can/candump_recorder.h"
#include "runtime/handoffs.h"

namespace xr::canlink {

class CanService {
 public:
  using Report = std::function<void(const std::string&)>;
  static constexpr double kPollPeriodS = 0.01;  // how often the caller polls

  CanService(rt::Handoffs& handoffs, Report report) : h_(handoffs), report_(std::move(report)) {}

  // `batteryTemp`: the BMS's temperature (0x356) is the battery temperature
  // input (Handoffs::batteryTemp, source bms). Only when no battery DS18B20
  // is configured: that hand-off has one writer.
  void setBmsBus(std::unique_ptr<BusSlot> slot, can::BmsProtocol protocol, bool batteryTemp = false);
  // `version` goes into product information (126996).
  void setN2kBus(std::unique_ptr<BusSlot> slot, std::uint8_t preferredAddress, std::string version);
  // --can-log: every frame sent and received on every bus, from now on.
  void setLog(can::CandumpSink* sink) { sink_ = sink; }

  void poll(TimeNs now);

  // For tests and /api/system: what the BMS link has seen.
  const BmsCanLink* bmsLink() const { return bmsLink_.get(); }

 private:
  BusSlot::Fault faultEvents(int bus);
  void publishStatus(TimeNs now);  // Handoffs::canStatus, for /api/system
  rt::Handoffs& h_;
  Report report_;
  ReportGate n2kErrorGate_;
  can::CandumpSink* sink_ = nullptr;
  std::unique_ptr<BusSlot> bms_;
  can::BmsProtocol protocol_ = can::BmsProtocol::Victron;
  bool batteryTemp_ = false;
  TimeNs pollNow_ = 0;
  std::unique_ptr<can::RecordingCanBus> bmsRecorded_;
  std::unique_ptr<BmsCanLink> bmsLink_;
  std::unique_ptr<BusSlot> n2k_;
  std::uint8_t n2kAddress_ = 35;
  std::string version_;
  std::unique_ptr<can::RecordingCanBus> n2kRecorded_;
  std::unique_ptr<N2kNode> n2kNode_;
};

}  // namespace xr::canlink

#pragma once
// What the integrations publish, taken from one telemetry snapshot (the
// seqlock the web server reads too; never a queue from the control thread).
// Each integration converts to its own units from here: Signal K wants SI
// (K, Hz, ratio 0-1, s), Home Assistant wants what a boat owner reads
// (degC, %, kWh).
#include <limits>
#include <string>
#include <string_view>

#include "core/inputs.h"
#include "core/modes.h"
#include "owner/owner_model.h"
#include "runtime/handoffs.h"

namespace xr::integrations {

struct IntegrationSample {
  bool valid = false;  // false before the first tick
  double battery_v = 0, battery_a = 0, alt_a = 0;
  double alt_temp_c = 0;
  double battery_temp_c = kNoValue;  // not measured yet (NaN)
  double rpm = 0;
  double field_pct = 0;  // duty
  bool field_on = false;
  bool alarm = false;
  double setpoint_v = 0, setpoint_a = 0;
  double soc_pct = 0;
  double time_to_empty_s = -1;  // < 0: unknown
  double power_w = 0;           // alternator output: battery voltage x alternator current
  double charged_kwh = 0;       // lifetime energy into the battery
  // What the regulator learns (NaN until measured; docs/batteries.md, docs/operations.md).
  double capacity_measured_ah = std::numeric_limits<double>::quiet_NaN();
  double nominal_v = 12;  // the bank's class, for energies
  double battery_r_mohm = std::numeric_limits<double>::quiet_NaN();
  double alt_run_hours = 0, alt_life_used_pct = 0, belt_slip_events = 0;
  std::string mode, stage, reason;
  ChargeStage stageValue = ChargeStage::BULK;
  bool operatorOff = false;  // sysMode SYS_MODE_OFF: switched off by a command
  // The owner model's words (docs/dashboard.md "Owner model"): the same
  // function as the dashboard's, so Home Assistant and Signal K say what it says.
  std::string ownerState;                                       // "Charging · Bulk · limited by Belt limit"
  std::string limitedBy;                                        // "Belt limit: 100 A", "nothing"
  double limitAmps = std::numeric_limits<double>::quiet_NaN();  // the first limit's amps
  std::vector<owner::OwnerLimit> limits;  // every limit acting now, most restrictive first
  std::string socSource = "unknown";      // bms | counted | ocv_estimate | unknown
};

IntegrationSample sampleOf(const rt::RuntimeSnapshot& s, const owner::OwnerContext& ctx = {});

// Signal K's chargingMode words for a stage (bulk / acceptance / float /
// other): absorption is "acceptance", idle or a field that is off is "other".
std::string_view signalKChargingMode(ChargeStage stage, bool fieldOn);

}  // namespace xr::integrations

#pragma once
// AlarmPanel: CheckAlarms(), the GPIO21 buzzer of docs/protections.md
// "Protections": one row per condition of the buzzer table (alarm_rows.h),
// evaluated every ALARM_CHECK_MS (250 ms) and held between, the
// AlarmLatchEnabled latch and the dashboard's acknowledgement
// (docs/protections.md "Acknowledging an alarm").
#include <array>

#include "core/inputs.h"
#include "core/time.h"
#include "params/params.h"
#include "protection/alarm_rows.h"
#include "protection/protection_log.h"

namespace xr {

// The rows the control side reports between ticks (docs/protections.md).
struct ControlAlarmRows {
  bool bmsStale = false;      // the BMS limits went stale (BmsLimiter)
  bool bmsMismatch = false;   // the BMS's values do not fit the bank
  bool chargingHeld = false;  // charging held for long with the engine running
};

// What one check reads.
struct AlarmInput {
  double TempToUse = kNoValue;     // the alternator temperature the protections use
  bool tempStale = false;          // T5: no valid reading
  double IBV = kNoValue;           // INA228 bus voltage
  double MeasuredAmps = kNoValue;  // alternator current
  double Bcur = kNoValue;          // battery current
  bool inaLatched = false;         // the INA228 latch
  bool tempTaskHung = false;       // T4
  bool faultMode = false;          // the sequencer runs a fault mode
  bool effAnomaly = false;         // efficiency anomaly alarm
};

class AlarmPanel {
 public:
  AlarmPanel() noexcept { messageAt_.fill(-1); }
  // Returns the GPIO21 level.
  bool update(const AlarmInput& in, const Params& p, const ProtectionLog& log) noexcept;
  void setBmsStale(bool stale) noexcept { control_.bmsStale = stale; }
  void setChargeChecks(bool bmsMismatch, bool chargingHeld) noexcept {
    control_.bmsMismatch = bmsMismatch;
    control_.chargingHeld = chargingHeld;
  }

  void resetLatch() noexcept { latched_ = false; }
  // The buzzer goes quiet for the rows sounding now (and a latch is
  // released); a row that was not sounding starts it again; once every row
  // is quiet the acknowledgement ends, so the next alarm sounds.
  void acknowledge(TimeNs now) noexcept;
  bool acknowledged() const noexcept { return ackActive_; }
  bool buzzer() const noexcept { return buzzer_; }
  bool latched() const noexcept { return latched_; }

 private:
  using Rows = std::array<bool, kAlarmRowCount>;
  Rows evaluate(const AlarmInput& in, const Params& p, const ProtectionLog& log) noexcept;
  void updateAcknowledgement(bool cond, TimeNs now) noexcept;
  void logBuzzer(const ProtectionLog& log) noexcept;

  ControlAlarmRows control_;                        // the control side's rows
  TimeNs nextCheck_ = 0;                            // the next 250 ms check
  bool buzzer_ = false;                             // GPIO21, held between checks
  bool latched_ = false;                            // AlarmLatchEnabled latch
  std::array<TimeNs, kAlarmRowCount> messageAt_{};  // each row's last console message (30 s throttle)
  Rows rowOn_{};                                    // the rows sounding at the last check
  bool ackActive_ = false;                          // acknowledged from the dashboard
  Rows ackRows_{};                                  // the rows that were sounding then
  TimeNs ackQuietSince_ = -1;                       // every row quiet since
  bool buzzerLogged_ = false;                       // "Alarm ON" logged, "Alarm OFF" not yet
  TimeNs buzzerOffSince_ = -1;                      // buzzer off since (AlarmOff logging hold)
};

}  // namespace xr

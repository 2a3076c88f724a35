#pragma once
// TemperatureChecks: the alternator temperature protections of
// docs/protections.md: T1 warning, T2 sustained (latched until
// reenable_field), T3 critical, T4 TempTask heartbeat (buzzer only), T5 stale
// sensor, and the heat-soak hold after an engine stop (docs/deviations.md
// "Heat soak after an engine stop").
#include "core/inputs.h"
#include "core/time.h"
#include "params/params.h"
#include "protection/protection_log.h"

namespace xr {

struct TemperatureChecksInput {
  Reading temp;                  // the alternator temperature per TempSource (core/alternator_temperature.h)
  TimeNs tempTaskHeartbeat = 0;  // TempTask's last beat
  TimeNs boot = 0;               // the first tick (grace periods count from it)
  bool engineStopped = false;    // the RPM gate holds this tick (heat-soak rule)
};

class TemperatureChecks {
 public:
  void update(const TemperatureChecksInput& in, const Params& p, const ProtectionLog& log) noexcept;
  // reenable_field: T2's latch clears and its sustained timer restarts.
  void reenable() noexcept;

  double value() const noexcept { return value_; }  // TempToUse (NaN = none)
  bool warning() const noexcept { return t1_; }
  bool sustained() const noexcept { return t2_; }
  bool critical() const noexcept { return t3_; }
  bool taskHung() const noexcept { return t4_; }
  bool stale() const noexcept { return t5_; }
  bool soakHold() const noexcept { return soakHold_; }

 private:
  void updateLimits(double t, bool usable, bool engineStopped, const Params& p,
                    const ProtectionLog& log) noexcept;
  void updateSoak(double t, bool usable, bool engineStopped, const Params& p,
                  const ProtectionLog& log) noexcept;

  double value_ = kNoValue;  // the reading the checks saw (alarms, telemetry)
  SustainTimer t1Held_;      // T1 held continuously (T2's timer)
  EventEdge evT1_, evT3_;    // trip/clear of T1 and T3
  EventEdge evT5_;           // clear of T5 (its trip has its own wording)
  bool t4Logged_ = false;    // TempTaskHung logged for this hang
  bool soakLogged_ = false;  // the heat-soak trip logged, its clear not yet
  bool t1_ = false;          // T1: above TemperatureLimitF + TempWarnExcess
  bool t2_ = false;          // T2: T1 held TempSustainedTimeout; latched until reenable
  bool t3_ = false;          // T3: above TemperatureLimitF + TempCritExcess (sticky while unusable)
  bool t4_ = false;          // T4: TempTask heartbeat older than TEMP_TASK_TIMEOUT
  bool t5_ = false;          // T5: no valid reading (stale, NaN, out of range)
  bool soakHold_ = false;    // above the limit since an engine stop
};

}  // namespace xr

// VoltageChecks::update(): hard shutdown, disagreement, implausibility.
#include "protection/voltage_checks.h"

#include <cmath>

#include "core/finite.h"
#include "params/constants.h"
#include "params/derived.h"

namespace xr {

void VoltageChecks::update(const VoltageChecksInput& in, const Params& p, const ProtectionLog& log) noexcept {
  // Alternator Hard Shutdown: IBV > AlternatorHardShutdownV.
  const double hs = alternatorHardShutdownV(p);
  altHs_ = finite(in.IBV) && in.IBV > hs;
  // Co-firing with the INA228 alert: one log line (InaLatchSet), not two.
  if (!(altHs_ && in.inaLatched))
    evAltHs_.update(altHs_, Reason::REASON_ALT_HARD_SHUTDOWN, in.IBV, hs, log, EventLevel::Error);
  updateDisagreement(in, p, log);
}

// Disagreement (warning, critical) and implausibility; nothing while the
// INA228 is absent, a sensor not read yet, or the INA228 latch suppresses it.
void VoltageChecks::updateDisagreement(const VoltageChecksInput& in, const Params& p,
                                       const ProtectionLog& log) noexcept {
  const TimeNs now = log.now();
  const bool inaUsable = !p.INADisconnected;
  bool disW = false, disC = false, impl = false;
  if (inaUsable && !in.notReadYet) {
    if (!in.suppressed) {
      const bool dead = !finite(in.BatteryV) || !finite(in.IBV) || in.BatteryV < k::SENSOR_DEAD_V ||
                        in.IBV < k::SENSOR_DEAD_V;
      const double diff = dead ? 0.0 : std::fabs(in.BatteryV - in.IBV);
      // NaN / < 0.1 V: critical at once, no debounce.
      disC = critT_.update(!dead && diff > criticalDisagreementThreshold(p), now,
                           fromMs(k::VoltageDisagreeCriticalTimeoutMs)) ||
             dead;
      disW =
          warnT_.update(!dead && diff > p.VoltageDisagreeThreshold, now, fromSec(p.VoltageDisagreeTimeout));
    }
    const VoltageRange range = plausibleVoltageRange(p);
    auto outside = [&](double v) { return !finite(v) || v < range.min || v > range.max; };
    impl = outside(in.IBV) && outside(in.BatteryV);  // single-sensor implausibility passes
  }
  if (!inaUsable || in.notReadYet || in.suppressed) {
    warnT_.reset();
    critT_.reset();
  }
  // The original firmware's console wording for either level.
  if ((disW && !evDisW_.logged) || (disC && !evDisC_.logged))
    log.push(EventCode::VoltageDisagreement, disC ? EventLevel::Critical : EventLevel::Error,
             disC ? Reason::REASON_VOLTAGE_DISAGREE_CRITICAL : Reason::REASON_VOLTAGE_DISAGREE_WARNING,
             in.BatteryV, in.IBV);
  evDisW_.update(disW, Reason::REASON_VOLTAGE_DISAGREE_WARNING, in.BatteryV, in.IBV, log, EventLevel::Error,
                 false);
  evDisC_.update(disC, Reason::REASON_VOLTAGE_DISAGREE_CRITICAL, in.BatteryV, in.IBV, log,
                 EventLevel::Critical, false);
  evImpl_.update(impl, Reason::REASON_VOLTAGE_IMPLAUSIBLE, in.IBV, in.BatteryV, log, EventLevel::Critical);
  disW_ = disW;
  disC_ = disC;
  impl_ = impl;
}

}  // namespace xr

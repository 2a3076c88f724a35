// RpmGate::update().
#include "protection/rpm_gate.h"

#include "core/finite.h"
#include "params/constants.h"

namespace xr {

void RpmGate::update(const RpmGateInput& in, const Params& p, const ProtectionLog& log) noexcept {
  const TimeNs now = log.now();
  const bool rpmLive = finite(in.rpm) && in.rpm >= p.MinRPMForField;
  if (in.fieldResting && !wasResting_) okAtRestStart_ = !below_;
  if (!in.fieldResting && wasResting_) restEndedAt_ = now;
  wasResting_ = in.fieldResting;
  const bool restHold =
      okAtRestStart_ &&
      (in.fieldResting || (restEndedAt_ >= 0 && now - restEndedAt_ < fromMs(k::RPM_REST_GRACE_MS)));
  below_ = !p.IgnoreRPM && !rpmLive && !restHold;
  // Before the first engine-speed reading the field stays off as above, but
  // nothing "tripped": the event waits for a reading that is really low
  // (docs/protections.md "First readings").
  if (finite(in.rpm)) everRead_ = true;
  if (everRead_ || !below_)
    ev_.update(below_, Reason::REASON_RPM_LOW, in.rpm, p.MinRPMForField, log, EventLevel::Info);
}

}  // namespace xr

// BankMismatchCheck::update().
#include "protection/bank_mismatch.h"

#include "core/finite.h"
#include "params/constants.h"
#include "params/derived.h"

namespace xr {

void BankMismatchCheck::update(const BankMismatchInput& in, const Params& p,
                               const ProtectionLog& log) noexcept {
  const SystemClass configured = systemClass(p);
  int live = 0, other = 0;
  double shown = 0.0;
  auto look = [&](double v) {
    if (!finite(v) || v < k::SENSOR_DEAD_V) return;
    ++live;
    if (bankClassOfVoltage(v) != configured) {
      ++other;
      shown = v;
    }
  };
  if (!p.INADisconnected) look(in.IBV);
  look(in.BatteryV);
  mismatch_ = held_.update(live > 0 && other == live, log.now(), fromMs(kHoldMs));
  ev_.update(mismatch_, Reason::REASON_BANK_MISMATCH, shown, nominalVoltage(configured), log,
             EventLevel::Critical);
}

}  // namespace xr

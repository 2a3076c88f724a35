// BankReading: the bank class read from the battery when nobody set it up.
#include "control/bank_reading.h"

#include <cmath>

namespace xr {

std::optional<SystemClass> BankReading::update(const Reading& ibv, TimeNs now) noexcept {
  const bool reading = ibv.stamp != 0 && std::isfinite(ibv.value);
  if (!waiting_) {
    waiting_ = true;
    since_ = now;
  }
  if (!reading && now - since_ < kWait) return std::nullopt;
  const std::optional<SystemClass> c = reading ? bankClassOfReading(ibv.value) : std::nullopt;
  const SystemClass used = c.value_or(SystemClass::V12);
  waiting_ = false;
  shown_ = {true, reading ? ibv.value : kNoValue, nominalVoltage(used), c.has_value()};
  return used;
}

}  // namespace xr

#include "store/ledger_check.h"

#include <cmath>
#include <sstream>

namespace xr {

namespace {

std::string number(double v) {
  std::ostringstream o;
  o.precision(6);
  o << v;
  return o.str();
}

}  // namespace

std::string dropImplausibleCapacity(BatteryLedger& l, double setCapacityAh) {
  CapacityLedger& c = l.capacity;
  std::string why;
  const bool finite = std::isfinite(c.SumAh) && std::isfinite(c.SumSwing) && std::isfinite(c.Cycles);
  if (!finite || c.SumAh < 0.0 || c.SumSwing < 0.0 || c.Cycles < 0.0) {
    why = "its sums are not finite or negative";
  } else if (c.Cycles > 0.0 && (c.SumAh == 0.0 || c.SumSwing == 0.0)) {
    why = "a swing was counted but its sums are zero";
  } else if (c.SumSwing > 0.0 && std::isfinite(setCapacityAh) && setCapacityAh > 0.0) {
    const double ah = c.SumAh / c.SumSwing;
    if (!std::isfinite(ah) || ah < kLedgerCapacityMinFactor * setCapacityAh ||
        ah > kLedgerCapacityMaxFactor * setCapacityAh)
      why = "its capacity " + number(ah) + " Ah is outside " + number(kLedgerCapacityMinFactor) + "x-" +
            number(kLedgerCapacityMaxFactor) + "x of the " + number(setCapacityAh) + " Ah set";
  }
  if (why.empty()) return "";
  // The known point (the SoC anchor) is its own measurement; it stays
  // unless it is not a number either.
  const CapacityLedger anchor = c;
  c = CapacityLedger{};
  if (std::isfinite(anchor.AnchorSocPct) && std::isfinite(anchor.NetAh) &&
      std::isfinite(anchor.AnchorAge_s)) {
    c.AnchorValid = anchor.AnchorValid;
    c.AnchorSocPct = anchor.AnchorSocPct;
    c.NetAh = anchor.NetAh;
    c.AnchorAge_s = anchor.AnchorAge_s;
  }
  return "the stored capacity measurement was dropped: " + why + "; it starts again from the next swings";
}

}  // namespace xr

#pragma once
// The health ledger checked on load (docs/batteries.md "Measured capacity"),
// like every other stored value: a damaged or edited row must not become a
// capacity the dashboard offers the owner in one tap.
#include <string>

#include "battery/ledger.h"

namespace xr {

// The measured capacity may lie within these factors of the set capacity
// (BatteryCapacity_Ah): a bank that lost 70 % is due for replacement, and
// one twice as large as set is a mistyped setting the set-up page should fix,
// not a measurement to trust.
inline constexpr double kLedgerCapacityMinFactor = 0.3;
inline constexpr double kLedgerCapacityMaxFactor = 2.0;

// Drops the capacity measurement of l (its sums and cycles; the known point
// too when it is not finite) when it is non-finite, negative, zero where a
// capacity would be computed from it, or its capacity lies outside
// 0.3x-2x of setCapacityAh. Returns what was dropped and why, for the
// journal and an event; "" when l is kept as it is.
std::string dropImplausibleCapacity(BatteryLedger& l, double setCapacityAh);

}  // namespace xr

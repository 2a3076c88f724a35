#pragma once
// The /api/status shape for programs (docs/dashboard.md): one naming style
// (snake_case) in the nested sections, numbers rounded to what the sensors
// resolve, whole numbers as integers, null for "no value" sentinels. The
// The CSV column names (docs/operations.md) stay as they are (they are snake_case already).
#include <boost/json.hpp>
#include <string>
#include <string_view>

#include "owner/owner_model.h"

namespace xr::web {

// Bumped whenever a key is renamed or removed (additions keep it).
inline constexpr int kStatusSchema = 2;

// "lockoutRemainingS" -> "lockout_remaining_s", "SOC_percent" -> "soc_percent",
// "g_awState" -> "aw_state", "cvDSlope" -> "cv_d_slope".
std::string snakeName(std::string_view name);

// Decimals a value named `name` keeps: volts 3 (INA228 resolves well below a
// millivolt, the ADS1115 path about 1 mV), amps 2, temperatures 1, percent 1,
// RPM 0, energy 1, seconds 2 (wall clock 3), anything else 4.
int statusDecimals(std::string_view name);

// The rounded value: null when not finite or a -999 "no value" sentinel,
// an integer when the rounded value is whole.
boost::json::value statusNumber(std::string_view name, double v);

// The owner model as JSON (docs/dashboard.md "Owner model"): {state, hero
// {value, unit, label}, soc {pct, source}, bms {state, words}, limits
// [{id, what, amps, why}]}, amps null for a limit that is not a current.
boost::json::object ownerToJson(const owner::OwnerModel& m);

}  // namespace xr::web

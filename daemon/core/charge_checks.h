#pragma once
// The vocabulary of the two checks that keep the regulator from silently
// not charging (docs/protections.md "BMS plausibility", "Charging held"):
// what of a BMS does not fit the bank, and what holds the charge. Shared by
// the core's detectors, the telemetry and the events' text.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "core/events.h"

namespace xr {

// What a BMS says that does not fit the bank (control/bms_plausibility.h).
enum class BmsMismatch : std::uint8_t { NONE, CVL_CLASS, CELL_VOLTAGE, PACK_VOLTAGE, WARNING_CELLS_NORMAL };
std::string_view toString(BmsMismatch m);

// What holds the charge while the engine runs and the bank is not full
// (control/charge_hold.h): the charge_held_by telemetry column.
enum class ChargeHold : std::uint8_t {
  NONE,
  BMS,              // a BMS on CAN: its CVL, CCL, warning, charge-disable (or its digital input)
  DVCC,             // a Victron GX's limits (DVCC)
  BATTERY_COLD,     // the battery's temperature rules: too cold to charge (or its cold cap)
  BATTERY_HOT,      // too warm to charge
  WEATHER,          // weather mode: the forecast promises sun
  ALTERNATOR_TEMP,  // the alternator's temperature (derating or its protection)
  PROTECTION,       // another protection holds the field off
  LIMIT,            // a setting's limit (speed table, a current or voltage limit)
};
std::string_view toString(ChargeHold h);

// describe()'s text of BmsMismatch and ChargingHeld events (nullopt for the rest).
std::optional<std::string> describeChargeChecks(const Event& e);

}  // namespace xr

// The names and text of the charge checks (see charge_checks.h).
#include "core/charge_checks.h"

#include <cmath>
#include <cstdio>

namespace xr {

std::string_view toString(BmsMismatch m) {
  switch (m) {
    case BmsMismatch::NONE:
      return "NONE";
    case BmsMismatch::CVL_CLASS:
      return "CVL_CLASS";
    case BmsMismatch::CELL_VOLTAGE:
      return "CELL_VOLTAGE";
    case BmsMismatch::PACK_VOLTAGE:
      return "PACK_VOLTAGE";
    case BmsMismatch::WARNING_CELLS_NORMAL:
      return "WARNING_CELLS_NORMAL";
  }
  return "?";
}

std::string_view toString(ChargeHold h) {
  switch (h) {
    case ChargeHold::NONE:
      return "NONE";
    case ChargeHold::BMS:
      return "BMS";
    case ChargeHold::DVCC:
      return "DVCC";
    case ChargeHold::BATTERY_COLD:
      return "BATTERY_COLD";
    case ChargeHold::BATTERY_HOT:
      return "BATTERY_HOT";
    case ChargeHold::WEATHER:
      return "WEATHER";
    case ChargeHold::ALTERNATOR_TEMP:
      return "ALTERNATOR_TEMP";
    case ChargeHold::PROTECTION:
      return "PROTECTION";
    case ChargeHold::LIMIT:
      return "LIMIT";
  }
  return "?";
}

namespace {

// What holds the charge, and what the owner checks, in words.
const char* holdText(ChargeHold h) {
  switch (h) {
    case ChargeHold::BMS:
      return "the BMS (its charge voltage, current limit, warning or charge-disable): check the BMS's "
             "alarms and settings";
    case ChargeHold::DVCC:
      return "the Victron GX's limits (DVCC): check the battery's limits on the GX";
    case ChargeHold::BATTERY_COLD:
      return "a cold battery (ChargeMinTempC): it charges again once it warms";
    case ChargeHold::BATTERY_HOT:
      return "a hot battery (ChargeMaxTempC): check the battery compartment's ventilation";
    case ChargeHold::WEATHER:
      return "weather mode (sun is forecast): the solar is expected to charge";
    case ChargeHold::ALTERNATOR_TEMP:
      return "the alternator's temperature: check its cooling and belt";
    case ChargeHold::PROTECTION:
      return "a protection: see the events before this one";
    case ChargeHold::LIMIT:
      return "a limit in the settings (the speed table, a current or voltage limit): check them on "
             "Settings";
    case ChargeHold::NONE:
      break;
  }
  return "nothing known";
}

std::string describeMismatch(const Event& e) {
  const auto kind = static_cast<BmsMismatch>(e.detail & 0xF);
  const int cells = (e.detail >> 4) & 0x3F, nominal = e.detail >> 10;
  char buf[320];
  switch (kind) {
    case BmsMismatch::CVL_CLASS:
      std::snprintf(buf, sizeof buf,
                    "BMS does not fit the bank: it reports a %.1f V charge voltage limit for this %d V bank "
                    "(%d cells): is it set up for %d cells? The regulator charges no higher than it allows",
                    e.a, nominal, cells, cells);
      break;
    case BmsMismatch::CELL_VOLTAGE:
      if (std::isfinite(e.b))
        std::snprintf(buf, sizeof buf,
                      "BMS does not fit the bank: it reports cells at %.2f V, this %d V bank's %d cells "
                      "average %.2f V: is it set up for %d cells? Its cell readings are not followed",
                      e.a, nominal, cells, e.b, cells);
      else
        std::snprintf(buf, sizeof buf,
                      "BMS does not fit the bank: it reports cells at %.2f V, which no lithium cell reads: "
                      "check its cell count and cell taps. Its cell readings are not followed",
                      e.a);
      break;
    case BmsMismatch::PACK_VOLTAGE:
      std::snprintf(buf, sizeof buf,
                    "BMS does not fit the bank: it measures %.2f V, the regulator %.2f V: check that the BMS "
                    "watches this %d V bank and its voltage sense wires",
                    e.a, e.b, nominal);
      break;
    case BmsMismatch::WARNING_CELLS_NORMAL:
      std::snprintf(buf, sizeof buf,
                    "BMS holds charging with a high-voltage warning while its highest cell reads %.2f V "
                    "(normal under %.2f V): check the BMS's cell voltage limits and alarms",
                    e.a, e.b);
      break;
    case BmsMismatch::NONE:
      std::snprintf(buf, sizeof buf, "BMS values fit the %d V bank again (%d cells)", nominal, cells);
      break;
  }
  return buf;
}

}  // namespace

std::optional<std::string> describeChargeChecks(const Event& e) {
  char buf[320];
  switch (e.code) {
    case EventCode::BmsMismatch:
      return describeMismatch(e);
    case EventCode::ChargingHeld:
      if (e.level == EventLevel::Info)
        std::snprintf(buf, sizeof buf, "Charging again after %.0f min held by %s", e.a,
                      std::string(toString(static_cast<ChargeHold>(e.detail))).c_str());
      else
        std::snprintf(buf, sizeof buf,
                      "Not charging for %.0f min with the engine running and the bank not full: held by %s",
                      e.a, holdText(static_cast<ChargeHold>(e.detail)));
      return buf;
    default:
      return std::nullopt;
  }
}

}  // namespace xr

#include "config/hardware_choices.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "config/integration_checks.h"

namespace xr {

std::optional<std::string> choiceNumberText(std::optional<double> v) {
  if (!v) return std::nullopt;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", *v);
  return std::string(buf);
}

std::optional<double> parseChoiceNumber(const std::optional<std::string>& text) {
  if (!text || text->empty()) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(text->c_str(), &end);
  if (end != text->c_str() + text->size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

bool isOneWireId(const std::string& id) {
  if (id.size() != 15 || id[2] != '-') return false;
  for (std::size_t i = 0; i < id.size(); ++i)
    if (i != 2 && !std::isxdigit(static_cast<unsigned char>(id[i]))) return false;
  return true;
}

bool isDs18b20Id(const std::string& id) {
  if (!isOneWireId(id) || !id.starts_with("28-")) return false;
  for (char c : id)
    if (std::isupper(static_cast<unsigned char>(c))) return false;  // the kernel writes lower case
  return true;
}

namespace {
std::string lowerCase(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}
}  // namespace

Settings withHardwareChoices(Settings s, const HardwareChoices& c) {
  if (c.batteryTempSensor) s.hardware.battery_temp_sensor = *c.batteryTempSensor;
  if (c.bmsInterface) s.can.bms_interface = *c.bmsInterface;
  if (c.pulleyRatio) s.hardware.frontend.pulley_ratio = *c.pulleyRatio;
  return s;
}

std::vector<std::pair<std::string, std::string>> checkBatteryProbe(const HardwareSettings& h) {
  std::vector<std::pair<std::string, std::string>> out;
  const std::string& probe = h.battery_temp_sensor;
  // One probe cannot be both: the alternator's reading would be taken for
  // the battery's, and a cold battery for a cool alternator. Hex digits
  // compare in either case: "28-0316A2794AFF" is the same probe.
  if (!probe.empty() && lowerCase(probe) == lowerCase(h.onewire_sensor_id))
    out.emplace_back("hardware.battery_temp_sensor",
                     "'" + probe + "' is the alternator's sensor ([hardware] onewire_sensor_id)");
  else if (!probe.empty() && !isDs18b20Id(probe))
    out.emplace_back("hardware.battery_temp_sensor",
                     "'" + probe + "' is not a DS18B20 id: 28- and 12 hex digits " +
                         "in lower case, as /sys/bus/w1/devices lists it " + "(e.g. 28-0316a2794aff)");
  const std::string& alt = h.onewire_sensor_id;
  if (!alt.empty() && !isDs18b20Id(alt))
    out.emplace_back("hardware.onewire_sensor_id",
                     "'" + alt + "' is not a DS18B20 id: 28- and 12 hex digits " +
                         "in lower case, as /sys/bus/w1/devices lists it " + "(e.g. 28-0316a2794aff)");
  return out;
}

std::vector<std::pair<std::string, std::string>> checkHardwareChoices(const Settings& file,
                                                                      const HardwareChoices& c) {
  const Settings s = withHardwareChoices(file, c);
  std::vector<std::pair<std::string, std::string>> out;
  for (auto& e : checkBatteryProbe(s.hardware)) out.push_back(std::move(e));
  // The file's range for the key (settings_schema.cpp); NaN fails both sides.
  const double ratio = s.hardware.frontend.pulley_ratio;
  if (!(ratio >= 0.01 && ratio <= 100.0))
    out.emplace_back("hardware.frontend.pulley_ratio",
                     "must be from 0.01 to 100 (alternator turns per engine turn)");
  for (auto& e : checkCan(s.can)) {
    // The set-up page sent the BMS bus: a clash with the NMEA 2000 bus is
    // that choice's error, filed under the setting it sent.
    if (c.bmsInterface && e.first == "can.n2k_interface" && e.second.starts_with("must not be the BMS bus"))
      e = {"can.bms_interface", "'" + s.can.bms_interface +
                                    "' is the NMEA 2000 bus ([can] n2k_interface): the two run at different "
                                    "bit rates"};
    out.push_back(std::move(e));
  }
  for (auto& e : checkIntegrations(s.integrations, s.can))
    if (e.first == "integrations.victron.enabled") out.push_back(std::move(e));  // the one rule across tables
  return out;
}

std::vector<std::pair<std::string, std::string>> layHardwareChoices(Settings& s, const HardwareChoices& c) {
  auto errors = checkHardwareChoices(s, c);
  if (errors.empty()) s = withHardwareChoices(std::move(s), c);
  return errors;
}

}  // namespace xr

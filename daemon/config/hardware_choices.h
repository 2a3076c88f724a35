#pragma once
// The set-up page's two hardware choices (docs/configuration.md "Set-up"):
// which 1-Wire probe is on the battery, and which CAN interface the BMS is
// on. They are file settings ([hardware] battery_temp_sensor, [can]
// bms_interface) that an owner with only a phone must still be able to make.
// Saved in the state database and laid over the file's at the next start:
// the devices are opened once, at start, before the field is driven.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "config/settings.h"

namespace xr {

struct HardwareChoices {
  // Unset: the file's value. Set to "": none, whatever the file says.
  std::optional<std::string> batteryTempSensor;
  std::optional<std::string> bmsInterface;
  // Alternator turns per engine turn: the tach reads the alternator, the RPM
  // tables are in engine RPM ([hardware.frontend] pulley_ratio).
  std::optional<double> pulleyRatio;
  bool operator==(const HardwareChoices&) const = default;
};

// The state database's keys (one small document each).
inline constexpr const char* kChoiceBatteryTempSensor = "setup.battery_temp_sensor";
inline constexpr const char* kChoiceBmsInterface = "setup.bms_interface";
inline constexpr const char* kChoicePulleyRatio = "setup.pulley_ratio";

// A number kept as text in the state database, exactly (%.17g), and read
// back; text that is not a number reads as no choice.
std::optional<std::string> choiceNumberText(std::optional<double> v);
std::optional<double> parseChoiceNumber(const std::optional<std::string>& text);

// A 1-Wire device id as sysfs names it: two hex digits of family, '-', twelve
// hex digits of serial ("28-0316a2794aff").
bool isOneWireId(const std::string& id);
// A DS18B20's id (family 28), in lower case as the kernel lists it: the
// only kind the docs ask for ([hardware] onewire_sensor_id,
// battery_temp_sensor).
bool isDs18b20Id(const std::string& id);

// The battery probe's id, as the file and the set-up page give it.
std::vector<std::pair<std::string, std::string>> checkBatteryProbe(const HardwareSettings& h);

// `s` with the choices laid over it.
Settings withHardwareChoices(Settings s, const HardwareChoices& c);

// (dotted key, message) for every reason the settings that `c` gives could not
// run, by the same checks the file's settings pass; empty when usable.
std::vector<std::pair<std::string, std::string>> checkHardwareChoices(const Settings& file,
                                                                      const HardwareChoices& c);

// Lays `c` over `s` when the settings it gives pass checkHardwareChoices;
// otherwise leaves `s` as it is (the file's values run) and returns why. The
// daemon's start and --print-config both lay the stored choices this way.
std::vector<std::pair<std::string, std::string>> layHardwareChoices(Settings& s, const HardwareChoices& c);

}  // namespace xr

// WebApi: the set-up page's hardware choices (docs/configuration.md
// "Set-up"). The devices were opened at start, so a choice is saved for the
// next start and the page says so; it is checked now by the rules the file
// passes, so the next start cannot fail on it.
#include <spdlog/spdlog.h>

#include <filesystem>
#include <fstream>

#include "app/web_api.h"
#include "drivers/onewire/w1_therm.h"

namespace xr::app {

namespace {

// Network interfaces of type ARPHRD_CAN (280): SocketCAN buses, real or
// virtual (<linux/if_arp.h>).
std::vector<std::string> canInterfaces(const std::string& sysClassNet) {
  std::vector<std::string> out;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(sysClassNet, ec)) {
    std::ifstream type(e.path() / "type");
    int t = 0;
    if (type >> t && t == 280) out.push_back(e.path().filename().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

// The probe the alternator's reader uses: the configured one, else the
// first found that is not the battery's (Ds18b20Reader's rule).
std::string alternatorProbe(const HardwareSettings& h, const std::vector<std::string>& probes) {
  if (!h.onewire_sensor_id.empty()) return h.onewire_sensor_id;
  for (const auto& p : probes)
    if (p != h.battery_temp_sensor) return p;
  return "";
}

template <class T>
std::optional<T> edited(const web::ChoiceEdit<T>& e, const std::optional<T>& saved) {
  return e.touched ? e.value : saved;
}

std::string describe(const char* what, const std::optional<std::string>& v, const std::string& file) {
  if (!v) return std::string(what) + " back to the file's (" + (file.empty() ? "none" : file) + ")";
  return std::string(what) + " " + (v->empty() ? "none" : *v);
}

}  // namespace

web::HardwareSetup WebApi::hardwareSetup() {
  web::HardwareSetup h;
  const HardwareChoices saved = ctx_.store ? ctx_.store->loadHardwareChoices() : HardwareChoices{};
  h.savable = ctx_.store != nullptr;
  h.batteryTempSensor = {ctx_.fileSettings.hardware.battery_temp_sensor, saved.batteryTempSensor,
                         ctx_.runningSettings.hardware.battery_temp_sensor};
  h.bmsInterface = {ctx_.fileSettings.can.bms_interface, saved.bmsInterface,
                    ctx_.runningSettings.can.bms_interface};
  h.pulleyRatio = {ctx_.fileSettings.hardware.frontend.pulley_ratio, saved.pulleyRatio,
                   ctx_.runningSettings.hardware.frontend.pulley_ratio};
  h.probes = w1::listDs18b20(ctx_.w1Root);
  h.alternatorSensor = alternatorProbe(ctx_.runningSettings.hardware, h.probes);
  h.canInterfaces = canInterfaces(ctx_.sysClassNet);
  h.victronBms = ctx_.runningSettings.integrations.victron.enabled;
  return h;
}

std::vector<web::FieldError> WebApi::saveHardwareChoices(const web::HardwareChoiceEdit& edit,
                                                         const std::string& source) {
  if (!ctx_.store)
    return {{"setup", "no state database to keep the choice in: set it in the configuration file"}};
  std::lock_guard lock(patchMutex_);
  const HardwareChoices saved = ctx_.store->loadHardwareChoices();
  const HardwareChoices next{edited(edit.batteryTempSensor, saved.batteryTempSensor),
                             edited(edit.bmsInterface, saved.bmsInterface),
                             edited(edit.pulleyRatio, saved.pulleyRatio)};
  std::vector<web::FieldError> errors;
  for (auto& [key, message] : checkHardwareChoices(ctx_.fileSettings, next)) errors.push_back({key, message});
  // With no onewire_sensor_id the alternator reads the first probe found:
  // giving that one to the battery would swap the two at the next start.
  // (A named one is checkHardwareChoices's.)
  const HardwareSettings& running = ctx_.runningSettings.hardware;
  const std::string alternator =
      running.onewire_sensor_id.empty() ? alternatorProbe(running, w1::listDs18b20(ctx_.w1Root)) : "";
  if (next.batteryTempSensor && !alternator.empty() && *next.batteryTempSensor == alternator)
    errors.push_back(
        {"hardware.battery_temp_sensor",
         "'" + alternator + "' is the alternator's sensor; to swap them, name both in the file"});
  if (!errors.empty()) return errors;
  if (next == saved) return {};
  if (std::string why = ctx_.store->saveHardwareChoices(next); !why.empty()) return {{"setup", why}};
  std::string text = "Set-up by " + source + ":";
  if (next.batteryTempSensor != saved.batteryTempSensor)
    text += " " +
            describe("battery temperature probe", next.batteryTempSensor,
                     ctx_.fileSettings.hardware.battery_temp_sensor) +
            ";";
  if (next.bmsInterface != saved.bmsInterface)
    text += " " + describe("BMS on CAN", next.bmsInterface, ctx_.fileSettings.can.bms_interface) + ";";
  if (next.pulleyRatio != saved.pulleyRatio)
    text += " pulley ratio " +
            (next.pulleyRatio ? fmt::format("{:g}", *next.pulleyRatio)
                              : fmt::format("back to the file's ({:g})",
                                            ctx_.fileSettings.hardware.frontend.pulley_ratio)) +
            ";";
  text += " used from the next start of the regulator.";
  spdlog::info("{}", text);
  recordEvent("SetupHardware", text);
  return {};
}

}  // namespace xr::app

#include "app/param_change_text.h"

#include <algorithm>
#include <cstdio>

#include "params/derived.h"

namespace xr::app {

namespace {

// Enough digits for any catalogue value (resolutions of 0.001) without the
// 17-digit noise of a binary double.
std::string valueText(const ParamSpec& spec, double v) {
  if (spec.kind == ParamKind::Bool) return v != 0.0 ? "on" : "off";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

}  // namespace

std::string paramChangeText(const Params& before, const Params& after, const std::vector<std::string>& named,
                            const std::string& source) {
  std::string list;
  for (const ParamSpec& spec : catalogue()) {
    const bool asked = std::find(named.begin(), named.end(), spec.name) != named.end();
    const std::size_t n = spec.kind == ParamKind::Table ? RPM_TABLE_SIZE : 1;
    for (std::size_t i = 0; i < n; ++i) {
      const double a = spec.get(before, i), b = spec.get(after, i);
      if (a == b) continue;
      if (!list.empty()) list += "; ";
      list += spec.name;
      if (spec.kind == ParamKind::Table) list += " point " + std::to_string(i + 1);
      list += " " + valueText(spec, a) + " \u2192 " + valueText(spec, b);
      if (!asked) list += " (follows the battery profile)";
    }
  }
  if (list.empty()) return {};
  return "Settings changed by " + (source.empty() ? std::string("the web API") : source) + ": " + list;
}

bool isSetupSave(const std::vector<std::string>& named) {
  auto has = [&](const char* n) { return std::find(named.begin(), named.end(), n) != named.end(); };
  return has("BatteryProfile") && has("MaxTableValue");
}

std::string setupSummaryText(const Params& p) {
  static constexpr const char* kChemistry[] = {"LiFePO4", "AGM", "Flooded", "Gel", "Custom"};
  const int id = std::clamp(p.BatteryProfile, 0, 4);
  double belt = 0.0;
  for (double a : p.rpmCapCurrentTable) belt = std::max(belt, a);
  char buf[160];
  std::snprintf(buf, sizeof buf, "Set-up: %s %d V %.0f Ah, alternator %.0f A, belt %.0f A", kChemistry[id],
                nominalVoltage(systemClass(p)), p.BatteryCapacity_Ah, p.MaxTableValue,
                std::min(belt, p.MaxTableValue));
  return buf;
}

}  // namespace xr::app

#include "config/battery_profiles.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "config/format.h"
#include "params/derived.h"

namespace xr {
namespace {

// Published 12 V values at 25 degC. Source keys are those of docs/sources.md
// (§0.2, §0.3); the section each number comes from is named beside it.
constexpr ProfileTable kTables[] = {
    // LiFePO4: 14.2 V absorption and 13.5 V float (VIC-CHG "Li-ion", VIC-LFP,
    // §3.8; BB 14.2-14.6 V); no float by default, a resting bank (BB "no
    // float needed", §3.6.3); revert 12.9 V, exit 15 A of a 500 Ah bank = 3 %
    // C and 1 h acceptance (TAR profile 8, §4.1.4); no temperature
    // compensation (VIC-LFP, BB, TAR); no charge below 0 degC (TAR 8, LISHEN,
    // SUNL, §3.7.2), full current from 5 degC (VIC-LFP "better not to charge
    // below 5 degC"), none above 45 degC (SUNL, LBS; BB IEC 62133 3-45 degC);
    // at most 0.5 C (SUNL, 15-45 degC). After absorption the bank rests
    // with the battery current held at 0 A while the alternator carries the
    // house loads, and re-bulks once 10 % of it was taken out (TAR profile 8:
    // "battery amps regulated to 0", revert -50 Ah of 500 Ah, §4.1.4).
    {BatteryProfileId::lifepo4, 4, 14.2, 14.2, 13.5, 12.9, false, 0.03, 1.0, 0.5, 0.0, -10.0, 50.0, 0.0, 5.0,
     45.0, true, true, 10.0},
    // AGM: 14.4 V (LL 14.2-14.4, VIC-CHG "Normal", E82 14.4-14.7, §3.8);
    // float 13.3 V (LL 13.2-13.3); full at 0.5 % C tail (MS, CONC, §3.6.1);
    // about 3 h absorption (MV, §3.8); revert 12.8 V (TAR, §4.1.4);
    // -4 mV/degC/cell (TAR AGM 0.024 V/degC per 12 V, §3.7.1); 0.4 C
    // (MS tests charged Lifeline AGM at 0.4 C, §3.6.1).
    {BatteryProfileId::agm, 6, 14.4, 14.4, 13.3, 12.8, true, 0.005, 3.0, 0.4, -4.0, -10.0, 50.0, -45.0, -45.0,
     50.0, false, false, 0.0},
    // Flooded: 14.7 V = 2.45 V/cell (VIC-CHG "High", TROJ 2.45-2.58 V/cell,
    // TAR standard FLA 14.8 V); float 13.5 V (TAR FLA); end amps 2 % C20
    // (ROLLS, §3.6.1); about 4 h absorption (MV); -5 mV/degC/cell (TAR FLA,
    // TROJ, §3.7.1), compensation limited below -9 degC (TAR; -10 here);
    // at most C/5 (HP, ROLLS max 20 % of C20).
    {BatteryProfileId::flooded, 6, 14.7, 14.7, 13.5, 12.8, true, 0.02, 4.0, 0.2, -5.0, -10.0, 50.0, -45.0,
     -45.0, 50.0, false, false, 0.0},
    // Gel: 14.4 V = 2.40 V/cell and float 13.5 V = 2.25 V/cell (TROJ gel,
    // AMPLE, §3.8); exit 5 A of 500 Ah = 1 % C (TAR gel, §4.1.4); about 3 h
    // (MV); -5 mV/degC/cell (TROJ gel "always temperature-compensate",
    // §3.7.1); C/5 (HP, lead-acid).
    {BatteryProfileId::gel, 6, 14.4, 14.4, 13.5, 12.8, true, 0.01, 3.0, 0.2, -5.0, -10.0, 50.0, -45.0, -45.0,
     50.0, false, false, 0.0},
};

constexpr std::array<std::string_view, 24> kOwned{"BatteryCells",
                                                  "BulkVoltage",
                                                  "AbsorptionVoltage",
                                                  "FloatVoltage",
                                                  "RebulkVoltage",
                                                  "UseFloat",
                                                  "IdleZeroCurrent",
                                                  "RebulkDischarge_percent",
                                                  "TailCurrent_A",
                                                  "AbsorptionTimeoutMs",
                                                  "MaximumAllowedBatteryAmps",
                                                  "TempCompMvPerCellC",
                                                  "TempCompMinC",
                                                  "TempCompMaxC",
                                                  "ChargeMinTempC",
                                                  "ChargeFullCurrentTempC",
                                                  "ChargeMaxTempC",
                                                  "BatteryTempRequired",
                                                  "ChargedVoltage",
                                                  "VoltageAlarmHigh",
                                                  "VoltageAlarmLow",
                                                  "TailCurrent",
                                                  "PeukertRatedCurrent_A",
                                                  "TargetVoltageSetpoint"};

bool pinnedName(const NameSet& pinned, std::string_view n) { return pinned.find(n) != pinned.end(); }

}  // namespace

const ProfileTable* profileTable(BatteryProfileId id) {
  for (const auto& t : kTables)
    if (t.id == id) return &t;
  return nullptr;
}

std::string_view toString(BatteryProfileId id) {
  switch (id) {
    case BatteryProfileId::lifepo4:
      return "lifepo4";
    case BatteryProfileId::agm:
      return "agm";
    case BatteryProfileId::flooded:
      return "flooded";
    case BatteryProfileId::gel:
      return "gel";
    case BatteryProfileId::custom:
      return "custom";
  }
  return "custom";
}

int cellsForNominal(BatteryProfileId id, int nominalV) {
  const ProfileTable* t = profileTable(id);
  const int per12 = t ? t->cellsPer12V : 6;  // custom: lead-acid cells (compensation is a lead-acid rule)
  return per12 * std::max(1, nominalV / 12);
}

std::span<const std::string_view> profileOwnedNames() { return kOwned; }

ProfileApplied applyBatteryProfile(const Params& in, const NameSet& pinned) {
  ProfileApplied r{in, {}};
  Params& p = r.params;
  const Params defaults{};
  for (std::string_view n : kOwned) {
    if (pinnedName(pinned, n)) continue;
    const ParamSpec* s = findParam(n);
    s->set(p, 0, s->get(defaults, 0));
  }
  const auto id = static_cast<BatteryProfileId>(p.BatteryProfile);
  const ProfileTable* t = profileTable(id);
  if (!t) return r;

  // Cells: the user's, else the voltage class of a BulkVoltage the user set
  // (today's system class), else a 12 V bank.
  int cells = p.BatteryCells;
  if (cells <= 0) {
    const int nominal = pinnedName(pinned, "BulkVoltage") ? nominalVoltage(systemClass(p)) : 12;
    cells = cellsForNominal(id, nominal);
  }
  const double scale = static_cast<double>(cells) / t->cellsPer12V;
  const double cap = p.BatteryCapacity_Ah;
  auto put = [&](std::string_view n, double v) {
    if (pinnedName(pinned, n)) return;
    const ParamSpec* s = findParam(n);
    if (s->kind == ParamKind::Int || s->kind == ParamKind::Bool) v = std::round(v);
    s->set(p, 0, std::clamp(v, s->min, s->max));
    r.setByProfile.emplace(n);
  };
  put("BatteryCells", cells);
  put("BulkVoltage", t->bulkV12 * scale);
  put("AbsorptionVoltage", t->absorptionV12 * scale);
  put("FloatVoltage", t->floatV12 * scale);
  put("RebulkVoltage", t->rebulkV12 * scale);
  put("UseFloat", t->useFloat ? 1.0 : 0.0);
  put("IdleZeroCurrent", t->idleZeroCurrent ? 1.0 : 0.0);
  put("RebulkDischarge_percent", t->rebulkDischargePct);
  put("TailCurrent_A", t->tailFractionC * cap);
  put("AbsorptionTimeoutMs", t->absorptionHours * 3600.0 * 1000.0);
  put("MaximumAllowedBatteryAmps", t->maxChargeRateC * cap);
  put("TempCompMvPerCellC", t->tempCompMvPerCell);
  put("TempCompMinC", t->tempCompMinC);
  put("TempCompMaxC", t->tempCompMaxC);
  put("ChargeMinTempC", t->chargeMinC);
  put("ChargeFullCurrentTempC", t->chargeFullCurrentC);
  put("ChargeMaxTempC", t->chargeMaxC);
  put("BatteryTempRequired", t->tempRequired ? 1.0 : 0.0);
  // ChargedVoltage, VoltageAlarmHigh/Low and TargetVoltageSetpoint stay 0:
  // derived from the bank and the voltages above (params/derived.h), so they
  // follow a BulkVoltage the owner wrote as well as the profile's.
  // The SoC monitor's full-charge tail (% of C) and Peukert's rated current
  // (C/20) follow the same battery.
  put("TailCurrent", t->tailFractionC * 100.0);
  put("PeukertRatedCurrent_A", cap / 20.0);
  return r;
}

std::vector<std::string> profileValuesTheFileOverrides(const Params& effective, const NameSet& fileNames) {
  std::vector<std::string> out;
  if (!profileTable(static_cast<BatteryProfileId>(effective.BatteryProfile))) return out;
  // What the profile gives with nothing pinned but what shapes it: its name,
  // the capacity and the cells in force (the effective BatteryCells already
  // holds the count the profile took from the file's BulkVoltage class).
  const NameSet shaping{"BatteryProfile", "BatteryCells", "BatteryCapacity_Ah"};
  const Params fromProfile = applyBatteryProfile(effective, shaping).params;
  for (std::string_view n : kOwned) {
    if (!pinnedName(fileNames, n) || shaping.count(n)) continue;
    const ParamSpec* s = findParam(n);
    const double mine = s->get(effective, 0), theirs = s->get(fromProfile, 0);
    if (mine != theirs)
      out.push_back(std::string(n) + " = " + formatNumber(mine) + " (profile: " + formatNumber(theirs) + ")");
  }
  return out;
}

std::string profileShadowNotice(const Params& effective, const NameSet& fileNames) {
  const auto values = profileValuesTheFileOverrides(effective, fileNames);
  if (values.empty()) return "";
  std::string list;
  for (const auto& v : values) list += (list.empty() ? "" : ", ") + v;
  return "BatteryProfile = \"" +
         std::string(toString(static_cast<BatteryProfileId>(effective.BatteryProfile))) +
         "\": the configuration file sets " + list +
         " itself, and the file wins; delete or comment out those lines to follow the profile";
}

NameSet namesDifferingFromDefaults(const Params& p) {
  const Params defaults{};
  NameSet out;
  for (const auto& s : catalogue()) {
    const std::size_t n = s.kind == ParamKind::Table ? RPM_TABLE_SIZE : 1;
    for (std::size_t i = 0; i < n; ++i) {
      if (s.get(p, i) != s.get(defaults, i)) {
        out.emplace(s.name);
        break;
      }
    }
  }
  return out;
}

std::vector<ProfileProblem> checkProfileLimits(const Params& p) {
  std::vector<ProfileProblem> out;
  // Owner text: "degC" reads °C (the dashboard shows these messages).
  auto v = [](double x, const char* unit) {
    const std::string u(unit);
    return formatNumber(x) + " " +
           (u == "degC"           ? std::string("°C")
            : u == "mV/degC/cell" ? std::string("mV/°C/cell")
                                  : u);
  };
  if (p.ChargeMinTempC > p.ChargeFullCurrentTempC)
    out.push_back({"ChargeMinTempC", v(p.ChargeMinTempC, "degC") + " is above ChargeFullCurrentTempC " +
                                         v(p.ChargeFullCurrentTempC, "degC") +
                                         ": the temperature range is inverted"});
  if (p.ChargeFullCurrentTempC >= p.ChargeMaxTempC)
    out.push_back({"ChargeMaxTempC", v(p.ChargeMaxTempC, "degC") + " must be above ChargeFullCurrentTempC " +
                                         v(p.ChargeFullCurrentTempC, "degC") +
                                         ": the temperature range is inverted"});
  if (p.TempCompMinC >= p.TempCompMaxC)
    out.push_back({"TempCompMinC", v(p.TempCompMinC, "degC") + " must be below TempCompMaxC " +
                                       v(p.TempCompMaxC, "degC") + ": the compensation range is inverted"});
  const auto id = static_cast<BatteryProfileId>(p.BatteryProfile);
  if (id == BatteryProfileId::lifepo4) {
    // The published LiFePO4 charge ceiling: 3.65 V/cell (DBUS, YAM, §3.10.1;
    // BMS cut-offs sit at 3.80-3.85 V). Only "custom" may go above it.
    constexpr double kMaxCellV = 3.65;
    const int cells =
        p.BatteryCells > 0 ? p.BatteryCells : cellsForNominal(id, nominalVoltage(systemClass(p)));
    for (const char* n : {"BulkVoltage", "AbsorptionVoltage", "FloatVoltage"}) {
      const double val = findParam(n)->get(p, 0);
      const double perCell = val / cells;
      if (perCell > kMaxCellV + 1e-9)
        out.push_back({n, v(val, "V") + " is " + formatNumber(std::round(perCell * 1000.0) / 1000.0) +
                              " V/cell on " + std::to_string(cells) +
                              " cells, above the LiFePO4 limit 3.65 V/cell (use BatteryProfile = \"custom\" "
                              "to go beyond it)"});
    }
    if (p.TempCompMvPerCellC != 0.0)
      out.push_back(
          {"TempCompMvPerCellC", v(p.TempCompMvPerCellC, "mV/degC/cell") +
                                     ": LiFePO4 is charged without temperature compensation (limit 0)"});
    if (p.ChargeMinTempC < 0.0)
      out.push_back({"ChargeMinTempC",
                     v(p.ChargeMinTempC, "degC") + " is below the LiFePO4 limit 0 °C (lithium plating)"});
  }
  return out;
}

}  // namespace xr

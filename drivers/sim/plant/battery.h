#pragma once
// Battery bank built from cells in series (12/24/48 V: 4/8/16 LiFePO4 or
// 6/12/24 lead-acid cells). Per cell, an equivalent circuit:
//   v = OCV(SoC) ± h·H/2 + R0(T)·i + v1 + v2
//   v1: fast RC (seconds), v2: slow RC (tens of minutes to hours); both
//   also carry the end-of-charge overpotential
//     η(i, SoC) = b·ln(1 + i/(Q·g0·(1 − SoC + ε)^m))   (charging only)
//   that makes lead-acid accept less at absorption voltage and gives the
//   LiFePO4 CV taper; it relaxes through the RC branches, so a full bank
//   falls back toward its OCV at rest.
//   h: LiFePO4 charge/discharge hysteresis state (−1..1).
//   T: bank temperature, heated by its losses, coupled to the compartment
//   air; R0 and the RC resistances rise in the cold.
// Parameters, sources and fits: docs/simulator.md "Battery".
#include <optional>
#include <string_view>
#include <vector>

namespace xr::sim {

enum class Chemistry { lifepo4, agm, flooded, gel };
std::string_view toString(Chemistry c);
std::optional<Chemistry> parseChemistry(std::string_view name);

struct OcvPoint {
  double soc;     // 0..1
  double cell_v;  // rest voltage of one cell
};
// The published table for a chemistry (per cell).
std::vector<OcvPoint> defaultOcvTable(Chemistry c);
// Empty when the table is usable; else why not (needs >= 2 points, SoC and
// voltage strictly rising, SoC within 0..1 and covering 0 and 1).
std::string_view ocvTableProblem(const std::vector<OcvPoint>& t);

struct BatteryConfig {
  Chemistry chemistry = Chemistry::lifepo4;
  double capacity_ah = 400.0;
  double soc_pct = 50.0;
  double nominal_v = 12.0;
  int cells = 0;              // in series; 0 = from nominal_v
  double r_ohm = 0.0;         // bank ohmic resistance at 25 °C; 0 = typical for chemistry and capacity
  double temp_c = 25.0;       // initial temperature, and the compartment air unless set otherwise
  bool temp_sensor = false;   // a DS18B20 on the bank, read as the battery temperature (docs/batteries.md)
  std::vector<OcvPoint> ocv;  // per cell; empty = defaultOcvTable(chemistry)
};

class BatteryModel {
 public:
  explicit BatteryModel(const BatteryConfig& c);
  // Terminal voltage with `amps` into the battery (+ = charging): linear in
  // the current within a step (the states move in step()).
  double terminalVolts(double amps) const noexcept { return emf_ + r_ * amps; }
  double emf() const noexcept { return emf_; }  // terminal voltage at zero current now
  double seriesR() const noexcept { return r_; }
  void step(double amps, double dt) noexcept;
  double socPct() const noexcept { return soc_ * 100.0; }
  void setSocPct(double p) noexcept;
  double ocv() const noexcept { return ocv_; }  // rest voltage at this SoC (hysteresis branch included)
  double tempC() const noexcept { return tempC_; }
  void setTempC(double c) noexcept;  // the bank and its compartment air
  void setAirC(double c) noexcept { airC_ = c; }
  int cells() const noexcept { return cells_; }
  double hysteresis() const noexcept { return h_; }
  const BatteryConfig& config() const noexcept { return cfg_; }

 private:
  void refreshOcv() noexcept;
  void refreshTemperature() noexcept;
  void refreshEmf() noexcept { emf_ = ocv_ + v1_ + v2_; }
  BatteryConfig cfg_;
  std::vector<OcvPoint> table_;
  int cells_;
  double cap_;
  // Per-chemistry constants (bank level where a voltage).
  double r25_, r1Rel_, r2Rel_, tau1_, tau2_, slowShare_, eocB_, eocG0_, eocM_, eocEps_, hystV_, eff_, heatC_,
      heatG_;
  double soc_, v1_ = 0.0, v2_ = 0.0, h_ = 0.0, tempC_, airC_;
  double r_ = 0.0, ocv_ = 0.0, emf_ = 0.0;
  double refreshedAtC_ = -1e9, rAtRefresh_ = 0.0, rSlope_ = 0.0;
  double kDt_ = -1.0, k1_ = 0.0, k2_ = 0.0;
  double eocSoc_ = -1.0, eocG_ = 1.0;  // g(SoC) of the end-of-charge overpotential, cached
  std::size_t seg_ = 0;                // table segment of the last lookup
};

}  // namespace xr::sim

#include "drivers/sim/plant/battery.h"

#include <algorithm>
#include <cmath>

namespace xr::sim {
namespace {

bool isLead(Chemistry c) { return c != Chemistry::lifepo4; }

// Resistance rise in the cold, Arrhenius-shaped: B chosen so that R(−20 °C)
// is 2.75 x R(25 °C), the middle of the "+150-200 % at −20 °C" quoted for
// LiFePO4 (docs/sources.md P3.4, LOW-AUTH). No lead-acid figure exists there;
// the same law is used for lead.
constexpr double kArrheniusB = 1697.0;
double coldFactor(double tC) { return std::exp(kArrheniusB * (1.0 / (tC + 273.15) - 1.0 / 298.15)); }

struct Chem {
  double cellNominalV;
  double rAhPerCell;    // R0 x capacity per cell at 25 °C, Ω·Ah
  double r1Rel, r2Rel;  // RC resistances relative to R0
  double tau1, tau2;    // s
  double slowShare;     // share of the end-of-charge overpotential in the slow branch
  double eocB, eocG0, eocM, eocEps;
  double hystCellV;    // full charge/discharge OCV gap per cell
  double eff;          // coulombic efficiency on charge
  double heatJPerKWh;  // heat capacity per Wh of nominal energy, J/K
  double coolWPerKWh;  // conductance to the air per Wh, W/K
};

Chem chemOf(Chemistry c) {
  if (!isLead(c)) {
    // LiFePO4. R0: 0.1 Ω·Ah per cell = 4 mΩ for a 12 V 100 Ah bank, between
    // the cells' 4 x 0.2 mΩ AC (EVE LF105) and drop-in packs' <= 15-20 mΩ
    // (UPOW, VEND-12V). tau2 15 min: a charged bank settles in 30 min
    // (deespaek) to an hour or two (KiloVault). End-of-charge constants
    // chosen so a 0.5C charge at 14.2 V holds CV 20-60 min (Battle Born >=
    // 20 min, Mastervolt ~30 min) before 0.02C, and a full bank takes no
    // more than ~0.03C at 14.5 V (no gassing in LiFePO4). Hysteresis gap 15 mV/cell,
    // the middle of ACCURE's 5-25 mV. Efficiency 0.99 (docs/sources.md P3.9).
    return {3.2, 0.1, 0.5, 0.5, 30.0, 900.0, 0.5, 0.11, 3.0, 1.3, 0.006, 0.015, 0.99, 8.0, 0.0025};
  }
  // Lead-acid (AGM fit; flooded and gel share it, with their OCV tables).
  // R0 0.5 Ω·Ah per 12 V (UNCONFIRMED: docs/sources.md has no lead DC figure).
  // tau2 2 h: rest 6 h or more before an OCV reading (Trojan, Odyssey).
  // End-of-charge constants fitted (tools/plots/fit_agm_taper.cpp) to Rod
  // Collins' Lifeline GPL-31T at 14.4 V from 50 %: absorption reached at
  // ~63 % SoC at 0.4C and ~77 % at 0.2C, full (0.5 % C tail) after ~5.5 h.
  // Efficiency 0.95 (Odyssey, Victron BMV default); flooded 0.85 below.
  return {2.0,       0.5 / 6.0, 0.5,        1.0, 60.0, 7200.0, 0.2,   0.09891,
          0.0266897, 0.68046,   0.00131325, 0.0, 0.95, 20.0,   0.0025};
}

}  // namespace

std::string_view toString(Chemistry c) {
  switch (c) {
    case Chemistry::lifepo4:
      return "lifepo4";
    case Chemistry::agm:
      return "agm";
    case Chemistry::flooded:
      return "flooded";
    case Chemistry::gel:
      return "gel";
  }
  return "?";
}

std::optional<Chemistry> parseChemistry(std::string_view n) {
  for (auto c : {Chemistry::lifepo4, Chemistry::agm, Chemistry::flooded, Chemistry::gel})
    if (toString(c) == n) return c;
  return std::nullopt;
}

std::vector<OcvPoint> defaultOcvTable(Chemistry c) {
  switch (c) {
    case Chemistry::lifepo4:
      // Libre Solar BMS firmware table (docs/sources.md P3.1, LSOL), per cell.
      return {{0.00, 2.833}, {0.05, 3.132}, {0.10, 3.177}, {0.15, 3.190}, {0.20, 3.213}, {0.25, 3.226},
              {0.30, 3.240}, {0.35, 3.252}, {0.40, 3.262}, {0.45, 3.264}, {0.50, 3.265}, {0.55, 3.268},
              {0.60, 3.271}, {0.65, 3.275}, {0.70, 3.283}, {0.75, 3.296}, {0.80, 3.304}, {0.85, 3.308},
              {0.90, 3.309}, {0.95, 3.314}, {1.00, 3.392}};
    case Chemistry::agm:
    case Chemistry::gel:
      // Lifeline AGM (docs/sources.md P3.3, LL): 10.50/11.75/12.20/12.55/12.80 V
      // per 12 V at 0/25/50/75/100 %. Gel has no table there and uses it.
      return {{0.0, 10.50 / 6}, {0.25, 11.75 / 6}, {0.50, 12.20 / 6}, {0.75, 12.55 / 6}, {1.0, 12.80 / 6}};
    case Chemistry::flooded:
      // Libre Solar's lead-acid line (docs/sources.md P3.3, LSOL x 6).
      return {{0.0, 11.52 / 6},  {0.25, 11.84 / 6}, {0.35, 11.96 / 6},
              {0.50, 12.15 / 6}, {0.75, 12.47 / 6}, {1.0, 12.78 / 6}};
  }
  return {};
}

std::string_view ocvTableProblem(const std::vector<OcvPoint>& t) {
  if (t.size() < 2) return "needs at least 2 points";
  if (t.front().soc != 0.0 || t.back().soc != 1.0) return "must run from 0 to 100 % SoC";
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (!(t[i].cell_v > 0.0 && t[i].cell_v < 10.0)) return "cell voltage out of range (0, 10) V";
    if (i > 0 && !(t[i].soc > t[i - 1].soc)) return "SoC must rise strictly";
    if (i > 0 && !(t[i].cell_v > t[i - 1].cell_v))
      return "voltage must rise strictly with SoC (not monotone)";
  }
  return {};
}

BatteryModel::BatteryModel(const BatteryConfig& c)
    : cfg_(c),
      table_(c.ocv.empty() ? defaultOcvTable(c.chemistry) : c.ocv),
      tempC_(c.temp_c),
      airC_(c.temp_c) {
  const Chem k = chemOf(c.chemistry);
  cells_ =
      c.cells > 0 ? c.cells : std::max(1, int(std::lround(c.nominal_v / (isLead(c.chemistry) ? 2.0 : 3.0))));
  cap_ = std::max(1.0, c.capacity_ah);
  r25_ = c.r_ohm > 0.0 ? c.r_ohm : k.rAhPerCell * cells_ / cap_;
  r1Rel_ = k.r1Rel;
  r2Rel_ = k.r2Rel;
  tau1_ = k.tau1;
  tau2_ = k.tau2;
  slowShare_ = k.slowShare;
  eocB_ = k.eocB * cells_;
  eocG0_ = k.eocG0 * cap_;  // amps
  eocM_ = k.eocM;
  eocEps_ = k.eocEps;
  hystV_ = 0.5 * k.hystCellV * cells_;
  eff_ = c.chemistry == Chemistry::flooded ? 0.85 : k.eff;  // flooded: ~85 % (docs/sources.md P3.9)
  const double kwh = k.cellNominalV * cells_ * cap_ / 1000.0;
  // Assumed (not in docs/sources.md): ~8 kJ/K per kWh for LiFePO4 (~10 kg at
  // ~1 kJ/(kg·K) per 1.3 kWh), ~20 kJ/K per kWh for lead; ~2.5 W/K per kWh
  // to still air. Time constants of hours.
  heatC_ = k.heatJPerKWh * 1000.0 * kwh;
  heatG_ = k.coolWPerKWh * 1000.0 * kwh;
  soc_ = std::clamp(c.soc_pct / 100.0, 0.0, 1.0);
  refreshTemperature();
  refreshOcv();
  refreshEmf();
}

void BatteryModel::setSocPct(double p) noexcept {
  soc_ = std::clamp(p / 100.0, 0.0, 1.0);
  refreshOcv();
  refreshEmf();
}

void BatteryModel::setTempC(double c) noexcept {
  tempC_ = airC_ = c;
  refreshTemperature();
}

void BatteryModel::refreshTemperature() noexcept {
  refreshedAtC_ = tempC_;
  rAtRefresh_ = r25_ * coldFactor(tempC_);
  rSlope_ = -rAtRefresh_ * kArrheniusB / ((tempC_ + 273.15) * (tempC_ + 273.15));  // dR/dT there
  r_ = rAtRefresh_;
}

void BatteryModel::refreshOcv() noexcept {
  // Linear between the table points; the last segment is cached (SoC moves
  // by parts per million per step).
  const std::size_t n = table_.size();
  if (seg_ + 1 >= n) seg_ = 0;
  while (seg_ > 0 && soc_ < table_[seg_].soc) --seg_;
  while (seg_ + 2 < n && soc_ > table_[seg_ + 1].soc) ++seg_;
  const OcvPoint& a = table_[seg_];
  const OcvPoint& b = table_[seg_ + 1];
  const double cellV = a.cell_v + (soc_ - a.soc) * (b.cell_v - a.cell_v) / (b.soc - a.soc);
  ocv_ = cellV * cells_ + h_ * hystV_;
}

void BatteryModel::step(double amps, double dt) noexcept {
  if (dt != kDt_) {
    kDt_ = dt;
    k1_ = 1.0 - std::exp(-dt / tau1_);
    k2_ = 1.0 - std::exp(-dt / tau2_);
  }
  // End-of-charge overpotential (charging only; continuous through 0 A).
  double eoc = 0.0;
  if (amps > 0.0) {
    if (std::fabs(soc_ - eocSoc_) > 1e-5) {  // the pow only when SoC moved
      eocSoc_ = soc_;
      eocG_ = eocG0_ * std::pow(1.0 - soc_ + eocEps_, eocM_);
    }
    eoc = eocB_ * std::log1p(amps / eocG_);
  }
  const double r0 = r_;
  v1_ += (r1Rel_ * r0 * amps + (1.0 - slowShare_) * eoc - v1_) * k1_;
  v2_ += (r2Rel_ * r0 * amps + slowShare_ * eoc - v2_) * k2_;
  // Hysteresis: the branch follows the direction of the charge, flipping
  // over ~3 % of the capacity.
  if (hystV_ > 0.0 && amps != 0.0) {
    const double w = std::min(1.0, std::fabs(amps) * dt / (0.03 * 3600.0 * cap_));
    h_ += ((amps > 0.0 ? 1.0 : -1.0) - h_) * w;
  }
  soc_ = std::clamp(soc_ + amps * dt * (amps > 0.0 ? eff_ : 1.0) / (3600.0 * cap_), 0.0, 1.0);
  // Heat: what the bank turns into heat (ohmic and polarisation), against
  // the compartment air.
  const double heat = std::max(0.0, amps * (r0 * amps + v1_ + v2_));
  tempC_ += (heat - heatG_ * (tempC_ - airC_)) / heatC_ * dt;
  // R follows the temperature smoothly: linear near the last exact value
  // (error < 1e-4 within 0.5 K), exact again beyond.
  if (std::fabs(tempC_ - refreshedAtC_) > 0.5)
    refreshTemperature();
  else
    r_ = rAtRefresh_ + rSlope_ * (tempC_ - refreshedAtC_);
  refreshOcv();
  refreshEmf();
}

}  // namespace xr::sim

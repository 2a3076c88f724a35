#include "drivers/sim/plant/battery.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace xr::sim {
namespace {
struct Pt {
  double soc, v;
};
// Rest voltage of a 12 V bank. LiFePO4: 4 cells, flat 3.25-3.35 V plateau, a
// steep knee above ~97 % and below ~10 %.
constexpr std::array<Pt, 12> kLfp{{{0.00, 10.0},
                                   {0.05, 12.0},
                                   {0.10, 12.8},
                                   {0.20, 13.0},
                                   {0.30, 13.1},
                                   {0.50, 13.2},
                                   {0.70, 13.28},
                                   {0.90, 13.35},
                                   {0.95, 13.42},
                                   {0.98, 13.6},
                                   {0.995, 13.95},
                                   {1.00, 14.7}}};
// Lead-acid rest voltages (6 cells).
constexpr std::array<Pt, 6> kAgm{
    {{0.0, 11.6}, {0.2, 11.95}, {0.4, 12.2}, {0.6, 12.45}, {0.8, 12.65}, {1.0, 12.9}}};
constexpr std::array<Pt, 6> kFlooded{
    {{0.0, 11.5}, {0.2, 11.8}, {0.4, 12.05}, {0.6, 12.3}, {0.8, 12.5}, {1.0, 12.7}}};
constexpr std::array<Pt, 6> kGel{
    {{0.0, 11.7}, {0.2, 12.0}, {0.4, 12.25}, {0.6, 12.5}, {0.8, 12.7}, {1.0, 12.95}}};

bool isLead(Chemistry c) { return c != Chemistry::lifepo4; }
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

BatteryModel::BatteryModel(const BatteryConfig& c) : cfg_(c) {
  const double cap = std::max(1.0, c.capacity_ah);
  const double scale = c.nominal_v / 12.0;
  // Typical pack resistance incl. cabling: LFP ~1 mΩ per 400 Ah, lead ~3x.
  const double base = isLead(c.chemistry) ? 1.2 / cap : 0.4 / cap;
  r_ = (c.r_ohm > 0.0 ? c.r_ohm : base * scale);
  r1_ = r_ * (isLead(c.chemistry) ? 1.5 : 0.8);
  tau1_ = isLead(c.chemistry) ? 120.0 : 60.0;
  switch (c.chemistry) {
    case Chemistry::lifepo4:
      eff_ = 0.99;
      break;
    case Chemistry::agm:
      eff_ = 0.95;
      break;
    case Chemistry::flooded:
      eff_ = 0.90;
      break;
    case Chemistry::gel:
      eff_ = 0.93;
      break;
  }
  socPerAmpSecond_ = 1.0 / (3600.0 * cap);
  setSocPct(c.soc_pct);
}

void BatteryModel::setSocPct(double p) noexcept {
  soc_ = std::clamp(p / 100.0, 0.0, 1.0);
  refreshOcv();
}

void BatteryModel::findSegment() noexcept {
  // soc_ left the cached segment: find the one holding it (linear
  // interpolation between the table points; flat outside the table).
  const Pt* t = kLfp.data();
  std::size_t n = kLfp.size();
  switch (cfg_.chemistry) {
    case Chemistry::lifepo4:
      break;
    case Chemistry::agm:
      t = kAgm.data(), n = kAgm.size();
      break;
    case Chemistry::flooded:
      t = kFlooded.data(), n = kFlooded.size();
      break;
    case Chemistry::gel:
      t = kGel.data(), n = kGel.size();
      break;
  }
  const double scale = cfg_.nominal_v / 12.0;
  if (soc_ <= t[0].soc) {
    segLo_ = -1e300, segHi_ = t[0].soc, segS0_ = 0.0, segV0_ = t[0].v * scale, segSlope_ = 0.0;
  } else if (soc_ > t[n - 1].soc) {
    segLo_ = t[n - 1].soc, segHi_ = 1e300, segS0_ = 0.0, segV0_ = t[n - 1].v * scale, segSlope_ = 0.0;
  } else {
    std::size_t i = 1;
    while (soc_ > t[i].soc) ++i;
    segLo_ = segS0_ = t[i - 1].soc;
    segHi_ = t[i].soc;
    segV0_ = t[i - 1].v * scale;
    segSlope_ = (t[i].v - t[i - 1].v) / (t[i].soc - t[i - 1].soc) * scale;
  }
}

// Every step (SoC moves by parts per million): inline, the segment search
// out of line.
inline void BatteryModel::refreshOcv() noexcept {
  if (!(soc_ > segLo_ && soc_ <= segHi_)) [[unlikely]]
    findSegment();
  ocv_ = segV0_ + (soc_ - segS0_) * segSlope_;
  leadX_ = isLead(cfg_.chemistry) ? std::clamp((soc_ - 0.75) * 4.0, 0.0, 1.0) : 0.0;  // 0 at 75 %, 1 at full
}

double BatteryModel::chargeOverpotential(double amps) const noexcept {
  // Lead chemistries stop accepting charge near full: an overpotential that
  // grows with SoC above 75 % and saturates with current (continuous through
  // 0 A), so at a fixed absorption voltage the current tapers to a tail.
  // (terminalVolts() skips the call when leadX_ is 0: LiFePO4, below 75 %.)
  if (leadX_ == 0.0 || amps <= 0.0) return 0.0;
  const double i0 = 0.01 * cfg_.capacity_ah;
  return 1.9 * leadX_ * leadX_ * (1.0 - std::exp(-amps / i0)) * cfg_.nominal_v / 12.0;
}

void BatteryModel::step(double amps, double dt) noexcept {
  if (dt != rcDt_) {
    rcDt_ = dt;
    rcA_ = std::exp(-dt / tau1_);
  }
  const double a = rcA_;
  vrc_ = vrc_ * a + amps * r1_ * (1.0 - a);
  const double soc = std::clamp(soc_ + amps * dt * (amps > 0.0 ? eff_ : 1.0) * socPerAmpSecond_, 0.0, 1.0);
  if (soc != soc_) {
    soc_ = soc;
    refreshOcv();
  }
}

}  // namespace xr::sim

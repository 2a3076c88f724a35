#pragma once
// Battery by chemistry: OCV(SoC) curve, series resistance, one RC
// polarisation branch, capacity, coulombic efficiency, a charge-acceptance
// overpotential near full for lead chemistries, and LiFePO4's flat plateau
// with its steep knee at both ends. Curves are for a 12 V bank and scale
// linearly with nominal_v (24/48 V banks).
#include <optional>
#include <string_view>

namespace xr::sim {

enum class Chemistry { lifepo4, agm, flooded, gel };
std::string_view toString(Chemistry c);
std::optional<Chemistry> parseChemistry(std::string_view name);

struct BatteryConfig {
  Chemistry chemistry = Chemistry::lifepo4;
  double capacity_ah = 400.0;
  double soc_pct = 50.0;
  double nominal_v = 12.0;
  double r_ohm = 0.0;  // series resistance; 0 = typical for chemistry and capacity
};

class BatteryModel {
 public:
  explicit BatteryModel(const BatteryConfig& c);
  // Terminal voltage while `amps` flow into the battery (+ = charging).
  double terminalVolts(double amps) const noexcept {
    return ocv_ + vrc_ + r_ * amps + (leadX_ == 0.0 || amps <= 0.0 ? 0.0 : chargeOverpotential(amps));
  }
  // Advance by dt with `amps` into the battery.
  void step(double amps, double dt) noexcept;
  // False when terminalVolts() is linear in the current (LiFePO4; lead below
  // 75 % SoC): the plant's node solve is then exact without refinement.
  bool hasOverpotential() const noexcept { return leadX_ != 0.0; }
  double socPct() const noexcept { return soc_ * 100.0; }
  void setSocPct(double p) noexcept;
  // Rest voltage at the present SoC (cached: recomputed only when SoC moves).
  double ocv() const noexcept { return ocv_; }
  double seriesR() const noexcept { return r_; }
  const BatteryConfig& config() const noexcept { return cfg_; }

 private:
  double chargeOverpotential(double amps) const noexcept;
  void refreshOcv() noexcept;   // after every SoC change
  void findSegment() noexcept;  // refreshOcv() when soc_ left the cached segment
  BatteryConfig cfg_;
  double soc_;                      // 0..1
  double r_;                        // series resistance, ohm
  double r1_;                       // polarisation resistance, ohm
  double tau1_;                     // polarisation time constant, s
  double vrc_ = 0;                  // polarisation voltage, V
  double eff_;                      // coulombic efficiency when charging
  double rcDt_ = -1.0, rcA_ = 0.0;  // cached exp(-dt/tau1)
  double socPerAmpSecond_;          // 1 / (3600 x capacity)
  double ocv_ = 0.0;                // OCV(soc_), see refreshOcv()
  double leadX_ = 0.0;              // lead charge-acceptance factor at soc_ (0 below 75 % and for LFP)
  // The OCV-curve segment soc_ lies in, (segLo_, segHi_], as a line in volts
  // already scaled to the bank: SoC moves by parts per million per step, so
  // refreshOcv() is a compare and a multiply-add almost every time.
  double segLo_ = 1.0, segHi_ = 0.0;                   // empty until the first refreshOcv()
  double segS0_ = 0.0, segV0_ = 0.0, segSlope_ = 0.0;  // ocv = V0 + (soc - S0) x slope
};

}  // namespace xr::sim

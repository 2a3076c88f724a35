#include "drivers/sim/plant/alternator.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace xr::sim {
namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kIdcPerIph = 3.0 * 1.4142135623730951 / kPi;
constexpr double kV1PerVdc = 1.4142135623730951 / kPi;
double fToC(double f) { return (f - 32.0) / 1.8; }
void setIf(double& dst, double v) {
  if (!std::isnan(v)) dst = v;
}
// Hot full-field output at the rating speed.
double ratedOutput(const LundellParams& m) {
  return outputAmps(m, 6000.0, fullFieldAmps(m, kRatingV, kHotC), kRatingV, kHotC);
}
}  // namespace

LundellParams resolveMachine(const AlternatorConfig& c) {
  LundellParams m = presetParams(c.preset);
  if (!std::isnan(c.cut_in_rpm)) {
    // The open-circuit voltage is speed x flux: scale the flux so that the
    // cold machine at full field reaches 14 V at the asked engine rpm.
    const double want = c.cut_in_rpm * c.pulley_ratio;
    if (want <= 0.0) throw std::invalid_argument("cut_in_rpm must be above 0");
    if (want >= kMaxAltRpm)
      throw std::invalid_argument("cut_in_rpm x pulley_ratio = " + std::to_string(int(want)) +
                                  " shaft rpm: the knee is above the maximum speed (18000 rpm)");
    m.flux_k *= cutInRpm(m) / want;
  }
  if (!std::isnan(c.rated_a)) {
    // Impedance scaling: dividing the stator impedance by z multiplies the
    // current at every speed by about z and leaves the knee where it is.
    // Heat capacity and cooling scale with it (a bigger machine).
    const LundellParams base = m;
    double z = 1.0;
    for (int i = 0; i < 8; ++i) {
      const double got = ratedOutput(m);
      if (!(got > 0.0)) throw std::invalid_argument("rated_a cannot be reached: no output at 6000 shaft rpm");
      z *= c.rated_a / got;
      m.stator_l_h = base.stator_l_h / z;
      m.stator_rx_ohm = base.stator_rx_ohm / z;
      m.copper_r_ohm = base.copper_r_ohm / z;
      m.stator_c_j_k = base.stator_c_j_k * z;
      m.case_c_j_k = base.case_c_j_k * z;
      m.stator_case_g_w_k = base.stator_case_g_w_k * z;
      m.case_air_g_w_k = base.case_air_g_w_k * z;
    }
    if (std::fabs(ratedOutput(m) - c.rated_a) > 0.01 * c.rated_a)
      throw std::invalid_argument("rated_a = " + std::to_string(c.rated_a) +
                                  " cannot be fitted to this machine");
  }
  setIf(m.pole_pairs, c.pole_pairs);
  setIf(m.flux_k, c.flux_k);
  setIf(m.flux_sat_a, c.flux_sat_a);
  setIf(m.stator_l_h, c.stator_l_h);
  setIf(m.stator_rx_ohm, c.stator_rx_ohm);
  setIf(m.copper_r_ohm, c.copper_r_ohm);
  setIf(m.field_r_ohm, c.field_r_ohm);
  setIf(m.field_l_h, c.field_l_h);
  setIf(m.diode_v, c.diode_v);
  if (!std::isnan(c.field_tau_s)) m.field_l_h = c.field_tau_s * m.field_r_ohm;
  const double cutIn = cutInRpm(m);
  if (!(cutIn < kMaxAltRpm))
    throw std::invalid_argument("the machine's knee (cut-in " + std::to_string(int(cutIn)) +
                                " shaft rpm at full field) is above the maximum speed (18000 rpm)");
  return m;
}

AlternatorModel::AlternatorModel(const AlternatorConfig& c) : AlternatorModel(c, resolveMachine(c)) {}

AlternatorModel::AlternatorModel(const AlternatorConfig& c, const LundellParams& m)
    : cfg_(c), m_(m), statorC_(fToC(c.temp_f)), caseC_(fToC(c.temp_f)), fieldRef_(kRatingV / m.field_r_ohm) {
  refreshTemperature();
}

void AlternatorModel::setSpeed(double engineRpm) noexcept {
  engineRpm_ = engineRpm;
  altRpm_ = std::max(0.0, engineRpm * cfg_.pulley_ratio);
  we_ = m_.pole_pairs * 2.0 * kPi * altRpm_ / 60.0;
  x_ = we_ * m_.stator_l_h;
  x2_ = x_ * x_;
  // Fan cooling grows with speed; a fifth of it remains at standstill
  // (convection). The shape is an assumption: docs/sources.md P2.11 has no
  // airflow numbers.
  gCaseAir_ = m_.case_air_g_w_k * (0.2 + 0.8 * std::min(2.0, altRpm_ / kFanRefRpm));
}

void AlternatorModel::refreshTemperature() noexcept {
  refreshedAtC_ = statorC_;
  const double f = copperFactor(statorC_);
  rcu_ = m_.copper_r_ohm * f;
  r_ = m_.stator_rx_ohm + rcu_;
  rf_ = m_.field_r_ohm * f;
  lagDt_ = -1.0;  // the field time constant moved
}

double AlternatorModel::outputAt(double terminalV, double* dIdV) const noexcept {
  const double e = we_ * m_.flux_k * m_.flux_sat_a * std::tanh(fieldA_ / m_.flux_sat_a) * 0.7071067811865476;
  const double v1 = kV1PerVdc * (terminalV + 2.0 * m_.diode_v);
  if (e <= v1) {
    if (dIdV) *dIdV = 0.0;
    return 0.0;
  }
  const double z2 = r_ * r_ + x2_;
  const double s = std::sqrt(z2 * e * e - x2_ * v1 * v1);
  if (dIdV) *dIdV = kIdcPerIph * kV1PerVdc * (-r_ - x2_ * v1 / s) / z2;
  return kIdcPerIph * (s - v1 * r_) / z2;
}

void AlternatorModel::step(double duty, double fieldV, double engineRpm, double ambientF,
                           double dt) noexcept {
  if (engineRpm != engineRpm_) setSpeed(engineRpm);
  if (std::fabs(statorC_ - refreshedAtC_) > 0.05) refreshTemperature();
  // Field: the PWM applies duty x supply on average; L/R lag, solved exactly.
  if (open_) {
    fieldA_ = 0.0;  // an open winding carries nothing
  } else {
    if (dt != lagDt_) {
      lagDt_ = dt;
      lagK_ = 1.0 - std::exp(-dt * rf_ / m_.field_l_h);
    }
    const double target = std::clamp(duty, 0.0, 1.0) * std::max(0.0, fieldV) / rf_;
    fieldA_ += (target - fieldA_) * lagK_;
  }
  // Heat: stator copper and field winding into the winding node, the diode
  // bridge (on the housing) into the case node. Iron, friction and windage
  // are left out: with these alone the Bosch preset runs at ~55 % efficiency
  // at its rated point, the published figure (docs/sources.md REMY).
  const double iph = amps_ / kIdcPerIph;
  const double pStator = 3.0 * iph * iph * rcu_ + fieldA_ * fieldA_ * rf_;
  const double pCase = 2.0 * m_.diode_v * amps_;
  const double flow = m_.stator_case_g_w_k * (statorC_ - caseC_);
  const double ambC = fToC(ambientF);
  statorC_ += (pStator - flow) / m_.stator_c_j_k * dt;
  caseC_ += (pCase + flow - gCaseAir_ * (caseC_ - ambC)) / m_.case_c_j_k * dt;
}

}  // namespace xr::sim

#pragma once
// Alternator: a Lundell machine (lundell.h) with its field circuit, stator
// impedance and diode bridge feeding the bus, and a two-node thermal model
// (windings, case) whose case node is what a temperature sensor on the
// housing reads. Output depends on the terminal voltage, so the plant solves
// the bus node with it (Plant::subStep).
#include <limits>

#include "drivers/sim/plant/lundell.h"

namespace xr::sim {

inline constexpr double kUnset = std::numeric_limits<double>::quiet_NaN();

struct AlternatorConfig {
  AlternatorPreset preset = AlternatorPreset::bosch_lix_180;
  // Conveniences fitted onto the preset (unset = the preset's own):
  double rated_a = kUnset;      // hot (kHotC) full-field output at 6000 shaft rpm, 13.5 V (ISO 8854 speed)
  double cut_in_rpm = kUnset;   // engine rpm where the cold machine at full field opens to 14 V
  double field_tau_s = kUnset;  // L_f / R_f at 20 °C
  // Physical parameters (unset = preset, after the fits above).
  double pole_pairs = kUnset;
  double flux_k = kUnset;
  double flux_sat_a = kUnset;
  double stator_l_h = kUnset;
  double stator_rx_ohm = kUnset;
  double copper_r_ohm = kUnset;
  double field_r_ohm = kUnset;
  double field_l_h = kUnset;
  double diode_v = kUnset;
  // State and installation.
  double temp_f = 80.0;       // initial temperature of both thermal nodes
  double ambient_f = 95.0;    // engine-room air
  double pulley_ratio = 2.5;  // alternator rpm / engine rpm
  double wiring_ohm = 0.003;  // alternator B+ to battery cable
};

// The machine a config describes: preset, then the fits, then the explicit
// physical values. Throws std::invalid_argument on a machine that cannot be
// built (knee above the maximum speed, rated output out of reach).
LundellParams resolveMachine(const AlternatorConfig& c);

class AlternatorModel {
 public:
  explicit AlternatorModel(const AlternatorConfig& c);
  AlternatorModel(const AlternatorConfig& c, const LundellParams& m);
  // Advance the field (duty 0..1 of the field supply voltage fieldV) and the
  // temperatures by dt, with the output current of the last solve.
  void step(double duty, double fieldV, double engineRpm, double ambientF, double dt) noexcept;
  // DC output into terminalV at the present field, speed and temperature;
  // dIdV (<= 0) its slope, for the node solve.
  double outputAt(double terminalV, double* dIdV = nullptr) const noexcept;
  void setOutput(double amps) noexcept { amps_ = amps; }
  double amps() const noexcept { return amps_; }
  double tempF() const noexcept { return caseC_ * 1.8 + 32.0; }  // the housing (sensor)
  double statorC() const noexcept { return statorC_; }
  double caseC() const noexcept { return caseC_; }
  double fieldAmps() const noexcept { return fieldA_; }
  // Field current as a fraction of full field at kRatingV, 20 °C.
  double field() const noexcept { return fieldA_ / fieldRef_; }
  double altRpm() const noexcept { return altRpm_; }
  void setOpen(bool open) noexcept { open_ = open; }
  const AlternatorConfig& config() const noexcept { return cfg_; }
  const LundellParams& machine() const noexcept { return m_; }

 private:
  void setSpeed(double engineRpm) noexcept;
  void refreshTemperature() noexcept;  // resistances and what depends on them
  AlternatorConfig cfg_;
  LundellParams m_;
  double fieldA_ = 0.0, amps_ = 0.0;
  double statorC_, caseC_;
  bool open_ = false;
  double fieldRef_;
  // Cached on speed changes: engine rpm, shaft rpm, ω_e, X_s, X_s², fan cooling.
  double engineRpm_ = -1.0, altRpm_ = 0.0, we_ = 0.0, x_ = 0.0, x2_ = 0.0, gCaseAir_ = 0.0;
  // Cached on temperature moves (> 0.05 K): R_s, R_f, copper R, field lag.
  double refreshedAtC_ = -1e9, r_ = 0.0, rf_ = 0.0, rcu_ = 0.0;
  double lagDt_ = -1.0, lagK_ = 0.0;
};

}  // namespace xr::sim

#pragma once
// Alternator: a current source. Output = rated x rpmCurve(rpm) x field x hot
// factor, where the field current lags the duty through field_tau_s. Below
// cut-in it makes nothing. Thermal: first-order, I^2 R heating (plus the
// field winding), cooling that improves with RPM (fan), calibrated so rated
// output at cruise RPM settles thermal_rise_f above ambient with
// thermal_tau_s: the defaults put a 30-minute full-output run well past
// TemperatureLimitF (150 degF) from any ambient, so the thermal loop matters.
namespace xr::sim {

struct AlternatorConfig {
  double rated_a = 120.0;         // hot output at full field, high RPM
  double field_tau_s = 0.15;      // field current lag behind the duty
  double temp_f = 80.0;           // initial alternator temperature
  double ambient_f = 95.0;        // engine-room air
  double pulley_ratio = 2.5;      // alternator RPM / engine RPM
  double cut_in_rpm = 600.0;      // engine RPM where output starts
  double full_rpm = 2000.0;       // engine RPM where rated output is reached
  double cruise_rpm = 1800.0;     // engine RPM the thermal calibration refers to
  double thermal_rise_f = 150.0;  // steady rise above ambient at rated output, cruise RPM
  double thermal_tau_s = 600.0;   // thermal time constant at cruise RPM
  double wiring_ohm = 0.003;      // alternator B+ to battery cable
};

class AlternatorModel {
 public:
  explicit AlternatorModel(const AlternatorConfig& c);
  // Advance by dt: fieldCmd 0..1 (duty x effective enable), engine RPM, ambient.
  void step(double fieldCmd, double engineRpm, double ambientF, double dt) noexcept;
  double amps() const noexcept { return amps_; }
  double tempF() const noexcept { return tempF_; }
  double field() const noexcept { return field_; }
  // Fraction 0..1 of rated output available at this RPM and temperature.
  double availableFraction(double engineRpm) const noexcept;
  void setOpen(bool open) noexcept { open_ = open; }
  const AlternatorConfig& config() const noexcept { return cfg_; }

 private:
  double coolingFactor(double engineRpm) const noexcept;
  double rpmCurve(double engineRpm) const noexcept;  // the RPM part of availableFraction (>= 0)
  double hotFactor() const noexcept;                 // the temperature part
  AlternatorConfig cfg_;
  double field_ = 0.0;
  double amps_ = 0.0;
  double tempF_;
  bool open_ = false;
  double lagDt_ = -1.0, lagK_ = 0.0;  // cached 1 - exp(-dt/field_tau_s)
  // RPM changes only on scenario events: its curve value and relative
  // cooling are cached per RPM instead of recomputed (sqrt, divisions) every step.
  double curveRpm_ = -1.0, curve_ = 0.0, coolRel_ = 1.0;
  double invRated_, invThermalTau_;  // reciprocals: no divisions per step
};

}  // namespace xr::sim

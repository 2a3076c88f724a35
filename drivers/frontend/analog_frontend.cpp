#include "drivers/frontend/analog_frontend.h"

#include <cmath>
#include <limits>

namespace xr::frontend {
namespace {
constexpr double kKelvin = 273.15;
double fToC(double f) { return (f - 32.0) * 5.0 / 9.0; }
double cToF(double c) { return c * 9.0 / 5.0 + 32.0; }
}  // namespace

double dividerGain(const AnalogFrontEndSettings& s) {
  return (s.divider_r_top_ohm + s.divider_r_bottom_ohm) / s.divider_r_bottom_ohm;
}
double rpmScale(const AnalogFrontEndSettings& s) {
  return s.rpm_per_volt / (s.pulley_ratio > 0.0 ? s.pulley_ratio : 1.0);
}

double batteryVoltsFromAdc(const AnalogFrontEndSettings& s, double v) { return v * dividerGain(s); }
double adcFromBatteryVolts(const AnalogFrontEndSettings& s, double v) { return v / dividerGain(s); }

double altAmpsFromAdc(const AnalogFrontEndSettings& s, double v) {
  const double a = (v - s.hall_zero_v) / s.hall_sensitivity_v_per_a;
  return s.hall_invert ? -a : a;
}
double adcFromAltAmps(const AnalogFrontEndSettings& s, double amps) {
  const double a = s.hall_invert ? -amps : amps;
  return s.hall_zero_v + a * s.hall_sensitivity_v_per_a;
}

double rpmFromAdc(const AnalogFrontEndSettings& s, double v) {
  const double rpm = v * rpmScale(s);
  return rpm < s.rpm_low_floor ? 0.0 : rpm;
}
double adcFromRpm(const AnalogFrontEndSettings& s, double rpm) { return rpm / rpmScale(s); }

double tempFFromAdc(const AnalogFrontEndSettings& s, double v) {
  // Node voltage V = Vs * Rth / (Rs + Rth)  =>  Rth = Rs * V / (Vs - V).
  if (!(v > 0.0) || !(v < s.thermistor_supply_v)) return std::numeric_limits<double>::quiet_NaN();
  const double r = s.thermistor_series_r_ohm * v / (s.thermistor_supply_v - v);
  const double invT =
      1.0 / (s.thermistor_t0_c + kKelvin) + std::log(r / s.thermistor_r0_ohm) / s.thermistor_beta;
  return cToF(1.0 / invT - kKelvin);
}
double adcFromTempF(const AnalogFrontEndSettings& s, double tempF) {
  const double t = fToC(tempF) + kKelvin;
  const double r =
      s.thermistor_r0_ohm * std::exp(s.thermistor_beta * (1.0 / t - 1.0 / (s.thermistor_t0_c + kKelvin)));
  return s.thermistor_supply_v * r / (s.thermistor_series_r_ohm + r);
}

}  // namespace xr::frontend

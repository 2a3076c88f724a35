#pragma once
// Analog front end of the upstream board, in ONE place shared by the real
// ADS1115 driver (volts -> quantity) and the simulator (quantity -> volts):
//   CH0 battery voltage through a resistive divider (1 MΩ / 75 kΩ),
//   CH1 alternator current from a Hall sensor (2.5 V at 0 A),
//   CH2 RPM from an LM2907 frequency-to-voltage converter,
//   CH3 alternator temperature from an NTC thermistor (beta model) in the
//       lower leg of a divider from the supply.
#include "config/settings.h"

namespace xr::frontend {

// The linear scale factors of CH0 and CH2, for callers that convert per
// sample and want them computed once from the settings (x * factor is
// bit-identical to the *FromAdc functions below, which use the same ones).
double dividerGain(const AnalogFrontEndSettings& s);  // battery volts per ADC volt
double rpmScale(const AnalogFrontEndSettings& s);     // engine RPM per ADC volt

// CH0
double batteryVoltsFromAdc(const AnalogFrontEndSettings& s, double adcVolts);
double adcFromBatteryVolts(const AnalogFrontEndSettings& s, double batteryVolts);
// CH1: amps before DynamicAltCurrentZero is subtracted.
double altAmpsFromAdc(const AnalogFrontEndSettings& s, double adcVolts);
double adcFromAltAmps(const AnalogFrontEndSettings& s, double amps);
// CH2: engine RPM (alternator RPM / pulley_ratio); readings under
// rpm_low_floor are reported as 0 (the LM2907 output offset is not rotation).
double rpmFromAdc(const AnalogFrontEndSettings& s, double adcVolts);
double adcFromRpm(const AnalogFrontEndSettings& s, double engineRpm);
// CH3: degrees Fahrenheit; NaN when the reading is outside the divider's
// range (open or shorted thermistor).
double tempFFromAdc(const AnalogFrontEndSettings& s, double adcVolts);
double adcFromTempF(const AnalogFrontEndSettings& s, double tempF);

}  // namespace xr::frontend

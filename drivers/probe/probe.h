#pragma once
// `xregulatord --probe` (issue 7): checks the I2C bus for both chips (IDs),
// the pwmchip, the gpio lines, the watchdog, the 1-Wire sensors and the
// serial port, and prints a report that tells a new user exactly what to fix.
// Returns 0 when everything required is present, 1 otherwise. The runtime
// wires it to the --probe flag.
#include <ostream>

#include "config/settings.h"

namespace xr {

int runProbe(const Settings& settings, std::ostream& out);

class I2cBus;
// For tests and simulation: probe the chips over `bus` instead of opening
// settings.hardware.i2c_bus.
int runProbe(const Settings& settings, std::ostream& out, I2cBus* busOverride);

}  // namespace xr

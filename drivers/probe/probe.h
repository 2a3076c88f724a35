#pragma once
// `xregulatord --probe` (docs/architecture.md): checks the I2C bus for both chips (IDs),
// the pwmchip, the gpio lines, the watchdog, the 1-Wire sensors and the
// serial port, and prints a report that tells a new user exactly what to fix.
// Returns 0 when everything required is present, 1 otherwise. The runtime
// wires it to the --probe flag.
#include <ostream>
#include <string>

#include "config/settings.h"

namespace xr {

int runProbe(const Settings& settings, std::ostream& out);

// The adapter's bus clock from the device tree
// (<sysRoot>/class/i2c-dev/i2c-N/device/of_node/clock-frequency, a
// big-endian u32), or 0 when unknown. The control tick reads INA228 and
// ADS1115 every 2.5 ms: at the Pi's default 100 kHz that alone takes most of
// the tick, so the probe asks for 400 kHz.
unsigned long readI2cClockHz(const std::string& devPath, const std::string& sysRoot = "/sys");

class I2cBus;
// For tests and simulation: probe the chips over `bus` instead of opening
// settings.hardware.i2c_bus.
int runProbe(const Settings& settings, std::ostream& out, I2cBus* busOverride);

}  // namespace xr

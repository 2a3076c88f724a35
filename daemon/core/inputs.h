#pragma once
// Inputs of one control tick: every sensor sample with its freshness, plus
// `now`. Built by the runtime from the drivers (the same code on the board
// and in simulation); the core never touches a device.
#include <limits>

#include "core/bms_limits.h"
#include "core/time.h"

namespace xr {

inline constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();

// One sensor channel. `stamp` is when the latest valid sample was taken
// (0 = never); `fresh` is true when that sample is new since the previous
// tick. `value` holds the latest sample (NaN when none was ever valid).
struct Reading {
  double value = kNoValue;
  TimeNs stamp = 0;
  bool fresh = false;
};

// Where Inputs::batteryTempC comes from (docs/batteries.md). One input, several
// sources: the battery DS18B20 on the 1-Wire bus today; a BMS over CAN
// (0x356 temperature) and a Victron device fill the same Reading later and
// name themselves here. `none`: no source is configured.
enum class BatteryTempSource { none, ds18b20, bms, victron };

struct Inputs {
  TimeNs now = 0;

  // INA228 (sign convention: Bcur positive = charging into the battery).
  bool inaPresent = false;         // detected and answering
  Reading IBV;                     // bus voltage, V
  Reading Bcur;                    // shunt current, A, before DynamicShuntGainFactor
  bool inaBusOvervoltage = false;  // DIAG_ALRT.BUSOL seen by the driver (hardware ALERT asserted)
  TimeNs inaDiagStamp = 0;         // when DIAG_ALRT was last read
  bool inaFastModeActive = false;  // the driver's conversion mode (fast while field on)
  double inaDieTempC = kNoValue;

  // ADS1115 channels, already scaled by the analog front end.
  Reading BatteryV;       // CH0, V
  Reading altCurrentRaw;  // CH1, A, before DynamicAltCurrentZero is subtracted
  Reading rpm;            // CH2, RPM (or the engine's speed for RpmSource = n2k)
  Reading thermistorF;    // CH3, degF

  // DS18B20 over 1-Wire (slow thread).
  Reading AlternatorTemperatureF;
  TimeNs tempTaskHeartbeat = 0;  // last time the temperature thread completed a cycle (T4)

  // Battery temperature (slow: a sample a second or slower), degC, with the
  // source that provides it. The core decides when it is too old.
  Reading batteryTempC;
  BatteryTempSource batteryTempSource = BatteryTempSource::none;

  // VE.Direct (slow thread).
  Reading VictronCurrent;  // A, + = charging
  Reading VictronVoltage;  // V
  Reading solarPowerW;     // PPV, W

  // Discrete inputs (already polarity-corrected).
  bool ignitionOn = true;
  bool bmsChargeEnabled = true;

  // The engine's speed from NMEA 2000 (127488) whenever a bus hears it, for
  // the belt-slip check against the tach (docs/operations.md "Belt slip").
  Reading engineRpm;

  // A BMS's charge limits (CAN or another source, slow thread); see bms_limits.h.
  BmsLimits bms;
};

}  // namespace xr

#pragma once
// INA228 driver (docs/install.md, wiring): detect by MANUFACTURER_ID/DEVICE_ID,
// configure CONFIG/ADC_CONFIG/SHUNT_CAL/DIAG_ALRT/BOVL, fast conversions while
// the field is on and slow averaging while it is off (`inaFastModeActive`),
// read VBUS/CURRENT/DIETEMP/DIAG_ALRT, count failed reads and re-detect after
// a run of failures (hot-plug), rate-limited.
//
// RT-safe: every method is noexcept, allocates nothing and blocks only inside
// I2cBus::transfer(). Call from the control thread only (not thread-safe).
#include <cstdint>

#include "core/inputs.h"
#include "core/time.h"
#include "drivers/hal/i2c_bus.h"

namespace xr {

struct Ina228Sample {
  double busVolts = kNoValue;   // VBUS, V                        -> Inputs::IBV
  double currentA = kNoValue;   // CURRENT, A (+ = charging)      -> Inputs::Bcur
  double dieTempC = kNoValue;   // DIETEMP, °C                    -> Inputs::inaDieTempC
  std::uint16_t diagAlrt = 0;   // last DIAG_ALRT read
  bool busOvervoltage = false;  // DIAG_ALRT.BUSOL: bus above BOVL (ALERT pin asserted)
  bool fresh = false;           // this poll() read a new VBUS/CURRENT pair
  TimeNs stamp = 0;             // when VBUS/CURRENT were last read OK (0 = never)
  TimeNs diagStamp = 0;         // when DIAG_ALRT was last read OK    -> Inputs::inaDiagStamp
};

struct Ina228Stats {
  unsigned long failedReads = 0;     // every failed transaction while present
  unsigned consecutiveFailures = 0;  // current run
  unsigned long redetects = 0;       // successful re-detections after loss
  unsigned long reconfigures = 0;    // register read-back mismatch (chip reset) repaired
  int lastError = 0;                 // errno of the last failure (ENODEV: wrong IDs)
};

class Ina228Driver {
 public:
  // A run of this many failed reads marks the chip absent (INADisconnected).
  static constexpr unsigned kFailRunForRedetect = 5;
  // Re-detection attempts while absent, at most one per this interval.
  static constexpr TimeNs kRedetectInterval = 1'000'000'000;
  // Die temperature and configuration read-back cadence.
  static constexpr TimeNs kHousekeepingInterval = 1'000'000'000;

  // `invertCurrent` flips the sign when the shunt is wired the other way
  // (the core wants + = charging into the battery).
  Ina228Driver(I2cBus& bus, std::uint16_t address, double shuntOhm, double maxCurrentA,
               bool invertCurrent = false) noexcept;
  // Not copyable: the poll messages point into the driver itself.
  Ina228Driver(const Ina228Driver&) = delete;
  Ina228Driver& operator=(const Ina228Driver&) = delete;

  // MANUFACTURER_ID == 0x5449 and DEVICE_ID bits 15:4 == 0x228. 0, ENODEV
  // (other chip), or the bus errno.
  int detect() noexcept;
  // Writes CONFIG (ADCRANGE), SHUNT_CAL, DIAG_ALRT (SLOWALERT, active low),
  // ADC_CONFIG (current fast/slow mode) and BOVL (the current limit).
  // EINVAL when the shunt/max current cannot be encoded in SHUNT_CAL.
  int configure() noexcept;
  // detect() + configure(); marks the chip present on success.
  int start(TimeNs now) noexcept;

  // Fast conversions while the field is on, slow averaging while it is off.
  // Writes ADC_CONFIG only on a change (a write restarts the conversion).
  int setFastMode(bool fast) noexcept;
  bool fastModeActive() const noexcept { return fast_; }  // -> Inputs::inaFastModeActive
  // BOVL = VoltageHardwareLimit (BulkVoltage + 0.3 V); call at start and on every
  // BulkVoltage change. Remembered and re-programmed after a re-detection.
  int setBusOvervoltageLimit(double volts) noexcept;

  // Once per control tick. Reads DIAG_ALRT every call and VBUS/CURRENT when a
  // new averaged result is due (conversion cycle of the current mode); once a
  // second, over four consecutive ticks (one register each), die temperature
  // and a read-back of ADC_CONFIG/BOVL/SHUNT_CAL (repairing a chip that reset
  // behind our back). While absent, re-detects at most once
  // per kRedetectInterval. Returns the latest sample (values persist; `fresh`
  // tells whether this call read new ones).
  const Ina228Sample& poll(TimeNs now) noexcept;

  bool present() const noexcept { return present_; }  // -> Inputs::inaPresent
  const Ina228Stats& stats() const noexcept { return stats_; }
  const Ina228Sample& sample() const noexcept { return sample_; }
  double currentLsb() const noexcept { return currentLsb_; }
  // Expected time between new results in the current mode.
  TimeNs conversionCycle() const noexcept;

 private:
  int readReg(std::uint8_t reg, std::size_t bytes, std::uint64_t* v) noexcept;
  int writeReg(std::uint8_t reg, std::uint16_t v) noexcept;
  void noteFailure(int err, TimeNs now) noexcept;
  void noteSuccess() noexcept { stats_.consecutiveFailures = 0; }
  int housekeepingStep() noexcept;

  I2cBus& bus_;
  std::uint16_t addr_;
  double shuntOhm_;
  double maxCurrentA_;
  bool invert_;
  double currentLsb_;
  bool lowRange_;
  bool fast_ = false;
  bool present_ = false;
  double bovlVolts_ = 0.0;  // 0 = not programmed (chip default 0x7FFF = never)
  TimeNs nextRead_ = 0;
  bool conversionRestarted_ = false;  // ADC_CONFIG written: wait a full cycle before reading
  TimeNs nextHousekeeping_ = 0;
  unsigned housekeepingPhase_ = 0;
  TimeNs nextRedetect_ = 0;
  Ina228Sample sample_;
  Ina228Stats stats_;
  // poll()'s combined transaction, built once: pointer DIAG_ALRT, read 2;
  // pointer VBUS, read 3; pointer CURRENT, read 3 (the first two messages
  // alone when no result is due). Declared last: initialised from addr_.
  std::uint8_t pollPtr_[3];
  std::uint8_t pollRx_[8] = {};
  I2cMsg pollMsgs_[6];
};

}  // namespace xr

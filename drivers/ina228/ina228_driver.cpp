#include "drivers/ina228/ina228_driver.h"

#include <cerrno>
#include <cmath>

#include "drivers/i2c/i2c_registers.h"
#include "drivers/ina228/ina228_registers.h"

namespace xr {

using namespace ina228;

Ina228Driver::Ina228Driver(I2cBus& bus, std::uint16_t address, double shuntOhm, double maxCurrentA,
                           bool invertCurrent) noexcept
    : bus_(bus),
      addr_(address),
      shuntOhm_(shuntOhm),
      maxCurrentA_(maxCurrentA),
      invert_(invertCurrent),
      currentLsb_(ina228::currentLsb(maxCurrentA)),
      lowRange_(useLowAdcRange(shuntOhm, maxCurrentA)),
      pollPtr_{DIAG_ALRT, VBUS, CURRENT},
      pollMsgs_{{addr_, false, &pollPtr_[0], 1}, {addr_, true, pollRx_, 2},
                {addr_, false, &pollPtr_[1], 1}, {addr_, true, pollRx_ + 2, 3},
                {addr_, false, &pollPtr_[2], 1}, {addr_, true, pollRx_ + 5, 3}} {}

int Ina228Driver::readReg(std::uint8_t reg, std::size_t bytes, std::uint64_t* v) noexcept {
  return i2creg::readReg(bus_, addr_, reg, bytes, v);
}
int Ina228Driver::writeReg(std::uint8_t reg, std::uint16_t v) noexcept {
  return i2creg::writeReg16(bus_, addr_, reg, v);
}

int Ina228Driver::detect() noexcept {
  std::uint64_t mfr = 0, dev = 0;
  int rc = readReg(MANUFACTURER_ID, 2, &mfr);
  if (rc == 0) rc = readReg(DEVICE_ID, 2, &dev);
  if (rc != 0) return rc;
  // Match the die ID only (bits 15:4): the revision nibble varies (facts §1.8).
  if (mfr != kManufacturerTI || ((dev >> 4) & 0xFFF) != kDieId) return ENODEV;
  return 0;
}

int Ina228Driver::configure() noexcept {
  const long cal = shuntCal(shuntOhm_, maxCurrentA_, lowRange_);
  if (cal < 0) return EINVAL;
  const std::uint16_t diag = kDiagAlrtConfig;
  const std::uint16_t bovl = bovlVolts_ > 0.0 ? bovlCode(bovlVolts_) : 0x7FFF;
  int rc = writeReg(CONFIG, lowRange_ ? CONFIG_ADCRANGE : 0);
  if (rc == 0) rc = writeReg(SHUNT_CAL, static_cast<std::uint16_t>(cal));
  // BOVL before DIAG_ALRT/ADC_CONFIG so the first compared result already
  // sees the limit.
  if (rc == 0) rc = writeReg(BOVL, bovl);
  if (rc == 0) rc = writeReg(DIAG_ALRT, diag);
  if (rc == 0) rc = writeReg(ADC_CONFIG, fast_ ? kAdcConfigFast : kAdcConfigSlow);
  return rc;
}

int Ina228Driver::start(TimeNs now) noexcept {
  int rc = detect();
  if (rc == 0) rc = configure();
  if (rc != 0) {
    present_ = false;
    stats_.lastError = rc;
    nextRedetect_ = now + kRedetectInterval;
    return rc;
  }
  present_ = true;
  stats_.consecutiveFailures = 0;
  // The result registers hold reset values (VBUS = 0 V) or the previous
  // mode's data until the first conversion of the new configuration ends:
  // reading them earlier would report a dead sensor (< 0.1 V = critical
  // disagreement) at every start.
  nextRead_ = now + conversionCycle();
  nextHousekeeping_ = now;
  housekeepingPhase_ = 0;
  return 0;
}

TimeNs Ina228Driver::conversionCycle() const noexcept {
  // Both cycles are compile-time constants (poll() asks after every read).
  static constexpr TimeNs kFastCycle = static_cast<TimeNs>(adcCycleUs(kAdcConfigFast)) * 1000;
  static constexpr TimeNs kSlowCycle = static_cast<TimeNs>(adcCycleUs(kAdcConfigSlow)) * 1000;
  return fast_ ? kFastCycle : kSlowCycle;
}

int Ina228Driver::setFastMode(bool fast) noexcept {
  if (fast == fast_) return 0;
  fast_ = fast;
  // The new mode is remembered even when absent: configure() applies it.
  if (!present_) return 0;
  const int rc = writeReg(ADC_CONFIG, fast ? kAdcConfigFast : kAdcConfigSlow);
  if (rc != 0) {
    // Report the mode the chip is really in (inaFastModeActive gates the
    // fast-OV protection); the caller asks again next tick.
    fast_ = !fast;
    ++stats_.failedReads;
    stats_.lastError = rc;
    return rc;
  }
  // A new cycle starts at the write: the first result of the new mode is due
  // one conversion cycle later (poll() re-arms nextRead_ from its `now`).
  conversionRestarted_ = true;
  return rc;
}

int Ina228Driver::setBusOvervoltageLimit(double volts) noexcept {
  if (!(volts > 0.0) || !std::isfinite(volts)) return EINVAL;
  bovlVolts_ = volts;
  if (!present_) return 0;
  const int rc = writeReg(BOVL, bovlCode(volts));
  if (rc != 0) stats_.lastError = rc;
  return rc;
}

void Ina228Driver::noteFailure(int err, TimeNs now) noexcept {
  ++stats_.failedReads;
  ++stats_.consecutiveFailures;
  stats_.lastError = err;
  if (stats_.consecutiveFailures >= kFailRunForRedetect) {
    present_ = false;
    nextRedetect_ = now + kRedetectInterval;
  }
}

int Ina228Driver::housekeepingStep() noexcept {
  // One register per tick (bounded I2C time per tick on a 100 kHz bus):
  // DIETEMP, then a read-back of ADC_CONFIG, BOVL and SHUNT_CAL. A brown-out
  // resets the chip to defaults (BOVL 0x7FFF = no hardware OV backup,
  // SHUNT_CAL 0x1000) while reads keep succeeding: any mismatch reconfigures.
  std::uint64_t v = 0;
  static constexpr std::uint8_t kRegs[] = {DIETEMP, ADC_CONFIG, BOVL, SHUNT_CAL};
  const std::uint8_t reg = kRegs[housekeepingPhase_];
  const int rc = readReg(reg, 2, &v);
  if (rc != 0) return rc;
  bool ok = true;
  switch (reg) {
    case DIETEMP:
      sample_.dieTempC = dieTempC(static_cast<std::uint16_t>(v));
      break;
    case ADC_CONFIG:
      ok = v == (fast_ ? kAdcConfigFast : kAdcConfigSlow);
      break;
    case BOVL:
      ok = v == (bovlVolts_ > 0.0 ? bovlCode(bovlVolts_) : 0x7FFFu);
      break;
    default:
      ok = static_cast<long>(v & 0x7FFF) == shuntCal(shuntOhm_, maxCurrentA_, lowRange_);
      break;
  }
  housekeepingPhase_ = (housekeepingPhase_ + 1) % 4;
  if (!ok) {
    ++stats_.reconfigures;
    housekeepingPhase_ = 0;
    conversionRestarted_ = true;
    return configure();
  }
  return 0;
}

const Ina228Sample& Ina228Driver::poll(TimeNs now) noexcept {
  sample_.fresh = false;
  if (!present_) {
    if (now >= nextRedetect_) {
      nextRedetect_ = now + kRedetectInterval;
      if (start(now) == 0) ++stats_.redetects;
    }
    // Readings resume next tick: detect + configure already used this
    // tick's bus time.
    return sample_;
  }

  // DIAG_ALRT every tick and, when a new averaged result is due, VBUS and
  // CURRENT: ONE combined transaction (pointer, read, pointer, read, ...
  // with repeated starts, which the chip allows), the same register
  // accesses in the same order as separate reads, one ioctl on the board.
  // DIAG_ALRT is transparent (ALATCH=0): reading it clears nothing, so a
  // transaction that fails part-way loses no alert.
  // After an ADC_CONFIG write the first result of the new mode is due one
  // conversion cycle after this (successful) poll: nothing to read now.
  const bool readResult = !conversionRestarted_ && now >= nextRead_;
  // The messages are built once (constructor) over pollPtr_/pollRx_.
  int rc = bus_.transfer({pollMsgs_, readResult ? 6u : 2u});
  if (rc != 0) {
    // Which message failed is unknown: nothing of this transaction is used.
    noteFailure(rc, now);
    return sample_;
  }
  noteSuccess();
  const std::uint8_t* const diagB = pollRx_;
  const std::uint8_t* const vbusB = pollRx_ + 2;
  const std::uint8_t* const curB = pollRx_ + 5;
  const auto diag = static_cast<std::uint16_t>((diagB[0] << 8) | diagB[1]);
  sample_.diagAlrt = diag;
  sample_.busOvervoltage = (diag & DIAG_BUSOL) != 0;
  sample_.diagStamp = now;
  if (conversionRestarted_) {
    conversionRestarted_ = false;
    nextRead_ = now + conversionCycle();
  }
  if (readResult) {
    const auto vbus =
        (static_cast<std::uint32_t>(vbusB[0]) << 16) | (static_cast<std::uint32_t>(vbusB[1]) << 8) | vbusB[2];
    const auto cur =
        (static_cast<std::uint32_t>(curB[0]) << 16) | (static_cast<std::uint32_t>(curB[1]) << 8) | curB[2];
    sample_.busVolts = vbusVolts(vbus);
    const double amps = currentAmps(cur, currentLsb_);
    sample_.currentA = invert_ ? -amps : amps;
    sample_.fresh = true;
    sample_.stamp = now;
    nextRead_ = now + conversionCycle();
  }

  if (now >= nextHousekeeping_) {
    rc = housekeepingStep();
    if (rc != 0) {
      noteFailure(rc, now);
      housekeepingPhase_ = 0;
    }
    // The next register next tick; a full round once per interval.
    if (housekeepingPhase_ == 0) nextHousekeeping_ = now + kHousekeepingInterval;
  }
  return sample_;
}

}  // namespace xr

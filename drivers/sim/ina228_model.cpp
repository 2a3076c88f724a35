// TI INA228 model: the conversion engine (raw samples, averaging windows,
// CURRENT/POWER/ENERGY/CHARGE arithmetic, limit comparisons). The register
// map and the I2C messages are in ina228_registers.cpp.
#include "drivers/sim/ina228_model.h"

#include <algorithm>
#include <climits>
#include <cmath>

namespace xr::sim {

using namespace ina228;

namespace {
constexpr std::int32_t kMax20 = (1 << 19) - 1;
constexpr std::int32_t kMin20 = -(1 << 19);
constexpr double kVbusLsb = 195.3125e-6;  // V
constexpr double kTempLsb = 7.8125e-3;    // °C

std::int32_t quantise20(double v, double lsb) {
  const double c = std::nearbyint(v / lsb);
  if (!(c == c)) return 0;  // NaN input: the ADC reads 0
  return static_cast<std::int32_t>(std::clamp(c, double(kMin20), double(kMax20)));
}
}  // namespace

Ina228Model::Ina228Model() { reset(); }

TimeNs Ina228Model::sampleTime() const noexcept {
  TimeNs us = 0;
  if (busActive()) us += kConvTimeUs[(adcConfig_ >> 9) & 7];
  if (shuntActive()) us += kConvTimeUs[(adcConfig_ >> 6) & 7];
  if (tempActive()) us += kConvTimeUs[(adcConfig_ >> 3) & 7];
  return fromUs(us);
}

TimeNs Ina228Model::updatePeriod() const noexcept {
  const int m = mode();
  if (m == 0 || m == 8) return 0;
  return sampleTime() * kAvgSamples[adcConfig_ & 7];
}

void Ina228Model::restartConversions() noexcept {
  // Writing ADC_CONFIG restarts the conversion (E2E228); CONVDLY delays the
  // first one in 2 ms steps.
  const int m = mode();
  samplesInWindow_ = 0;
  sumVsh_ = sumVbus_ = sumTemp_ = 0;
  if (m == 0 || m == 8) {
    running_ = false;
    return;
  }
  if (!continuous()) diag_ &= ~CNVRF;  // a new triggered conversion clears CNVRF
  running_ = true;
  sampleTime_ = sampleTime();
  avg_ = kAvgSamples[adcConfig_ & 7];
  publishDt_ = toSec(sampleTime_ * avg_);
  const TimeNs delay = fromMs(2 * ((config_ >> 6) & 0xFF));
  nextSample_ = now_ + delay + sampleTime_;
}

void Ina228Model::quantise() noexcept {
  codesValid_ = true;
  vshCode_ = quantise20(analog_.vshunt_v, (config_ & 0x10) ? 78.125e-9 : 312.5e-9);
  vbusCode_ = quantise20(analog_.vbus_v, kVbusLsb);
  const double tc = std::nearbyint(analog_.dietemp_c / kTempLsb);
  tcode_ = static_cast<std::int32_t>(std::clamp(tc == tc ? tc : 0.0, -32768.0, 32767.0));
  // The raw power only the SLOWALERT = 0 comparison uses (a DIAG_ALRT
  // write invalidates the codes, so it is computed when SLOWALERT clears).
  if (!(diag_ & SLOWALERT)) {
    const double curCode = shuntCal_ ? double(vshCode_) * 4096.0 / shuntCal_ : 0.0;
    const double pw = std::fabs(curCode) * double(vbusCode_) / 16384.0;
    rawPower_ = static_cast<std::uint32_t>(std::min(pw, double(0xFFFFFF)));
  }
}

void Ina228Model::convertTo(TimeNs t) noexcept {
  // The analog inputs are constant between two updates (the plant changes
  // them only between steps), so every raw sample in [now_, t] sees the same
  // values: batch them instead of looping per sample.
  if (running_ && nextSample_ <= t && !codesValid_) quantise();  // after a register write
  while (running_ && nextSample_ <= t) {
    const TimeNs st = sampleTime_;
    const int avg = avg_;
    const std::int64_t due = (t - nextSample_) / st + 1;  // raw samples due by t
    const std::int64_t k = std::min<std::int64_t>(due, avg - samplesInWindow_);
    now_ = nextSample_ + (k - 1) * st;
    const std::int32_t vsh = vshCode_, vb = vbusCode_, tcode = tcode_;
    sumVsh_ += vsh * k;
    sumVbus_ += vb * k;
    sumTemp_ += tcode * k;
    samplesInWindow_ += int(k);
    nextSample_ += k * st;
    if (!(diag_ & SLOWALERT)) {
      // Limits against each raw result (SLOWALERT = 0).
      compareLimits(vsh, vb, tcode, rawPower_);
    }
    if (samplesInWindow_ >= avg) {
      publish(publishDt_);
      if (!continuous()) running_ = false;  // triggered: one conversion, then shutdown
    }
  }
  now_ = t;
}

void Ina228Model::publish(double dt) noexcept {
  // The mean of the window's raw codes (the integer sums, < 2^30, convert
  // to double exactly).
  const double n = samplesInWindow_;
  samplesInWindow_ = 0;
  diag_ &= ~MATHOF;
  if (shuntActive()) vshunt_ = static_cast<std::int32_t>(std::nearbyint(double(sumVsh_) / n));
  if (busActive()) vbus_ = static_cast<std::int32_t>(std::nearbyint(double(sumVbus_) / n));
  if (tempActive()) dietemp_ = static_cast<std::int16_t>(std::nearbyint(double(sumTemp_) / n));
  sumVsh_ = sumVbus_ = sumTemp_ = 0;
  ++conversions_;

  // CURRENT = VSHUNT x SHUNT_CAL arithmetic: with SHUNT_CAL = 13107.2e6 x
  // CURRENT_LSB x R (x4 at ADCRANGE=1) the code is VSHUNT_code x 4096 / SHUNT_CAL
  // in both ranges. SHUNT_CAL = 0 reads CURRENT/POWER/ENERGY/CHARGE as 0.
  double cur = 0.0;
  if (shuntCal_ != 0) {
    cur = double(vshunt_) * 4096.0 / shuntCal_;
    if (config_ & 0x20) {
      // TEMPCOMP: R_adj = R (1 + (DIETEMP - 25) x TEMPCO / 1e6).
      const double dieC = dietemp_ * kTempLsb;
      cur /= 1.0 + (dieC - 25.0) * double(tempco_) * 1e-6;
    }
  }
  double curQ = std::nearbyint(cur);
  if (curQ > kMax20 || curQ < kMin20) {
    diag_ |= MATHOF;
    curQ = std::clamp(curQ, double(kMin20), double(kMax20));
  }
  current_ = static_cast<std::int32_t>(curQ);
  // POWER = |I| x VBUS / 3.2 in power LSBs = CURRENT_code x VBUS_code / 16384.
  double pw = std::fabs(double(current_)) * double(vbus_) / 16384.0;
  if (pw > double(0xFFFFFF)) {
    diag_ |= MATHOF;
    pw = double(0xFFFFFF);
  }
  power_ = shuntCal_ ? static_cast<std::uint32_t>(std::max(0.0, std::nearbyint(pw))) : 0;
  // ENERGY LSB = 16 x power LSB; CHARGE LSB = CURRENT_LSB (per second).
  if (shuntCal_) {
    // Accumulated as doubles: up to the 40-bit register range they keep
    // 13+ fractional bits, and the registers (integer parts) are taken only
    // when read, so a publish costs two multiply-adds, not a float->int
    // round trip per accumulator.
    energyAcc_ += double(power_) * dt * (1.0 / 16.0);
    if (energyAcc_ >= 0x1.0p40) {
      energyAcc_ -= 0x1.0p40;
      diag_ |= ENERGYOF;
    }
    chargeAcc_ += double(current_) * dt;
    if (chargeAcc_ >= 0x1.0p39 || chargeAcc_ <= -0x1.0p39 - 1.0) {
      chargeAcc_ = 0.0;  // rolls over to 0 and flags it (docs/sources.md D1.4)
      diag_ |= CHARGEOF;
    }
  }
  diag_ |= CNVRF;
  if (diag_ & SLOWALERT) compareLimits(vshunt_, vbus_, dietemp_, power_);
}

void Ina228Model::refreshLimits() noexcept {
  // A channel that is not measured never trips: its bound is out of reach.
  constexpr std::int32_t kNone = INT32_MAX, kNoneLow = INT32_MIN;
  limTemp_ = tempActive() ? std::int32_t(std::int16_t(tempLimit_)) : kNone;
  limSovl_ = shuntActive() ? std::int32_t(std::int16_t(sovl_)) * 16 : kNone;
  limSuvl_ = shuntActive() ? std::int32_t(std::int16_t(suvl_)) * 16 : kNoneLow;
  limBovl_ = busActive() ? std::int32_t(bovl_ & 0x7FFF) * 16 : kNone;
  limBuvl_ = busActive() ? std::int32_t(buvl_ & 0x7FFF) * 16 : kNoneLow;
  limPol_ = shuntActive() && busActive() && shuntCal_;
  std::uint16_t measured = 0;
  if (tempActive()) measured |= TMPOL;
  if (shuntActive()) measured |= SHNTOL | SHNTUL;
  if (busActive()) measured |= BUSOL | BUSUL;
  if (shuntActive() && busActive()) measured |= POL;
  measured_ = measured;
}

void Ina228Model::compareLimits(std::int32_t vsh, std::int32_t vb, std::int32_t tcode,
                                std::uint32_t pw) noexcept {
  // The bounds of the channels measured, taken when a register was written
  // (refreshLimits), not per comparison.
  std::uint16_t cond = 0;
  if (tcode > limTemp_) cond |= TMPOL;
  if (vsh > limSovl_) cond |= SHNTOL;
  if (vsh < limSuvl_) cond |= SHNTUL;
  if (vb > limBovl_) cond |= BUSOL;
  if (vb < limBuvl_) cond |= BUSUL;
  if (limPol_ && (pw >> 8) > pwrLimit_) cond |= POL;
  if (diag_ & ALATCH) {
    diag_ |= cond;
  } else {
    // Transparent: the flags follow the comparison of the channels measured.
    diag_ = static_cast<std::uint16_t>((diag_ & ~measured_) | cond);
  }
  limitActive_ = (diag_ & kLimitFlags) != 0;
}

}  // namespace xr::sim

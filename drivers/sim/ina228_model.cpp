#include "drivers/sim/ina228_model.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <climits>
#include <cmath>

#include "drivers/sim/fast_math.h"

namespace xr::sim {
namespace ina228 {
namespace {
// Register size in bytes by pointer value, 0 = reserved (read and write
// both look it up once per message: a table, not a switch).
constexpr std::array<std::uint8_t, 64> kRegSize = [] {
  std::array<std::uint8_t, 64> t{};
  for (std::uint8_t r : {CONFIG, ADC_CONFIG, SHUNT_CAL, SHUNT_TEMPCO, DIETEMP, DIAG_ALRT, SOVL, SUVL, BOVL,
                         BUVL, TEMP_LIMIT, PWR_LIMIT, MANUFACTURER_ID, DEVICE_ID})
    t[r] = 2;
  for (std::uint8_t r : {VSHUNT, VBUS, CURRENT, POWER}) t[r] = 3;
  for (std::uint8_t r : {ENERGY, CHARGE}) t[r] = 5;
  return t;
}();
}  // namespace

int regSize(std::uint8_t reg) noexcept { return reg < kRegSize.size() ? kRegSize[reg] : 0; }
}  // namespace ina228

using namespace ina228;

namespace {
constexpr std::int32_t kMax20 = (1 << 19) - 1;
constexpr std::int32_t kMin20 = -(1 << 19);
constexpr double kVbusLsb = 195.3125e-6;  // V
constexpr double kTempLsb = 7.8125e-3;    // °C
constexpr std::uint64_t kMask40 = (std::uint64_t{1} << 40) - 1;
constexpr double kInvAvg[8] = {1.0, 1.0 / 4, 1.0 / 16, 1.0 / 64, 1.0 / 128, 1.0 / 256, 1.0 / 512, 1.0 / 1024};

[[gnu::always_inline]] inline std::int32_t quantise20(double v, double lsb) {
  const double c = roundEven(v / lsb);
  if (!(c == c)) return 0;  // NaN input: the ADC reads 0
  return static_cast<std::int32_t>(std::clamp(c, double(kMin20), double(kMax20)));
}
bool isReadOnly(std::uint8_t reg) {
  return (reg >= VSHUNT && reg <= CHARGE) || reg == MANUFACTURER_ID || reg == DEVICE_ID;
}
}  // namespace

Ina228Model::Ina228Model() { reset(); }

void Ina228Model::reset() noexcept {
  config_ = 0x0000;
  codesValid_ = false;
  adcConfig_ = 0xFB68;
  shuntCal_ = 0x1000;
  tempco_ = 0;
  vshunt_ = vbus_ = current_ = 0;
  dietemp_ = 0;
  power_ = 0;
  energyAcc_ = chargeAcc_ = 0.0;
  diag_ = MEMSTAT;
  sovl_ = 0x7FFF;
  suvl_ = 0x8000;
  bovl_ = 0x7FFF;
  buvl_ = 0x0000;
  tempLimit_ = 0x7FFF;
  pwrLimit_ = 0xFFFF;
  limitActive_ = false;
  ptr_ = 0;
  restartConversions();  // power-on default is continuous bus + shunt + temperature
  refreshLimits();
}

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
  oneSampleUntil_ = 0;
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
  if (!(analog_.dietemp_c == tcodeC_)) {  // the die temperature rarely moves (NaN: always redone)
    tcodeC_ = analog_.dietemp_c;
    const double tc = roundEven(analog_.dietemp_c / kTempLsb);
    tcode_ = static_cast<std::int32_t>(std::clamp(tc == tc ? tc : 0.0, -32768.0, 32767.0));
  }
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
    // Samples due by t (the common case, a step shorter than one sample
    // pass, without the 64-bit division).
    const TimeNs late = t - nextSample_;
    const std::int64_t due = late < st ? 1 : late / st + 1;
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
  // The next update() may take one raw sample inline if it is not the
  // window's last (a result is due then) and SLOWALERT = 1 (no raw compare).
  if (running_ && (diag_ & SLOWALERT) && codesValid_) {
    windowLast_ = nextSample_ + TimeNs(avg_ - samplesInWindow_ - 1) * sampleTime_;
    armOneSample();
  } else {
    oneSampleUntil_ = 0;
  }
}

// Out of line: a result every ~1.8 control ticks, while convertTo() runs
// ~2 times per tick and would pay for publish()'s registers on every call.
[[gnu::noinline]] void Ina228Model::publish(double dt) noexcept {
  // The window holds exactly AVG samples (update() never overfills it), and
  // AVG is a power of two: multiplying by 1/n is exact, no division. The
  // integer sums (< 2^30) convert to double exactly: the same mean as a
  // double accumulation.
  const int n = samplesInWindow_;
  const double inv = n == avg_ ? kInvAvg[adcConfig_ & 7] : 1.0 / n;
  samplesInWindow_ = 0;
  diag_ &= ~MATHOF;
  if (shuntActive()) vshunt_ = static_cast<std::int32_t>(roundEven(double(sumVsh_) * inv));
  if (busActive()) vbus_ = static_cast<std::int32_t>(roundEven(double(sumVbus_) * inv));
  if (tempActive()) dietemp_ = static_cast<std::int16_t>(roundEven(double(sumTemp_) * inv));
  sumVsh_ = sumVbus_ = sumTemp_ = 0;
  ++conversions_;

  // CURRENT = VSHUNT x SHUNT_CAL arithmetic: with SHUNT_CAL = 13107.2e6 x
  // CURRENT_LSB x R (x4 at ADCRANGE=1) the code is VSHUNT_code x 4096 / SHUNT_CAL
  // in both ranges. SHUNT_CAL = 0 reads CURRENT/POWER/ENERGY/CHARGE as 0.
  double cur = 0.0;
  if (shuntCal_ != 0) {
    // x (4096 / SHUNT_CAL), cached: the product is within a few ulps of the
    // quotient, so it rounds to the same code unless the quotient is (next
    // to) an exact half, where the division decides.
    if (curScaleCal_ != shuntCal_) {
      curScaleCal_ = shuntCal_;
      curScale_ = 4096.0 / shuntCal_;
    }
    cur = double(vshunt_) * curScale_;
    if (std::fabs(std::fabs(cur - roundEven(cur)) - 0.5) < 1e-6) cur = double(vshunt_) * 4096.0 / shuntCal_;
    if (config_ & 0x20) {
      // TEMPCOMP: R_adj = R (1 + (DIETEMP - 25) x TEMPCO / 1e6).
      const double dieC = dietemp_ * kTempLsb;
      cur /= 1.0 + (dieC - 25.0) * double(tempco_) * 1e-6;
    }
  }
  double curQ = roundEven(cur);
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
  power_ = shuntCal_ ? static_cast<std::uint32_t>(std::max(0.0, roundEven(pw))) : 0;
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
      chargeAcc_ = 0.0;  // rolls over to 0 and flags it (datasheet-facts 1.4)
      diag_ |= CHARGEOF;
    }
  }
  diag_ |= CNVRF;
  if (diag_ & SLOWALERT) compareLimitsInline(vshunt_, vbus_, dietemp_, power_);
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

[[gnu::always_inline]] inline void Ina228Model::compareLimitsInline(std::int32_t vsh, std::int32_t vb,
                                                                    std::int32_t tcode,
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

// The per-raw-sample comparison (SLOWALERT = 0) stays a call: convertTo()
// keeps its registers for the sample loop.
void Ina228Model::compareLimits(std::int32_t vsh, std::int32_t vb, std::int32_t tcode,
                                std::uint32_t pw) noexcept {
  compareLimitsInline(vsh, vb, tcode, pw);
}

std::uint64_t Ina228Model::peek(std::uint8_t reg) const noexcept {
  switch (reg) {
    case CONFIG:
      return config_;
    case ADC_CONFIG:
      return adcConfig_;
    case SHUNT_CAL:
      return shuntCal_;
    case SHUNT_TEMPCO:
      return tempco_;
    case VSHUNT:
      return reg20(vshunt_);
    case VBUS:
      return reg20(vbus_);
    case DIETEMP:
      return std::uint16_t(dietemp_);
    case CURRENT:
      return reg20(current_);
    case POWER:
      return power_;
    case ENERGY:
      return std::uint64_t(energyAcc_) & kMask40;  // integer part (>= 0)
    case CHARGE:
      return std::uint64_t(std::int64_t(chargeAcc_)) & kMask40;  // truncated toward 0
    case DIAG_ALRT:
      return diag_;
    case SOVL:
      return sovl_;
    case SUVL:
      return suvl_;
    case BOVL:
      return bovl_;
    case BUVL:
      return buvl_;
    case TEMP_LIMIT:
      return tempLimit_;
    case PWR_LIMIT:
      return pwrLimit_;
    case MANUFACTURER_ID:
      return 0x5449;
    case DEVICE_ID:
      return 0x2281;
    default:
      return 0;
  }
}

inline int Ina228Model::readMsg(std::uint8_t* buf, std::size_t len) noexcept {
  if (ptr_ == DIAG_ALRT && len == 2) [[likely]] {
    // The read of every control tick, straight from diag_ (the general path
    // below gives the same bytes and side effects).
    readDiag(buf);
    return 0;
  }
  const int size = regSize(ptr_);
  if (len == 0 || size == 0 || len > std::size_t(size)) {
    ++protocolErrors_;
    return EREMOTEIO;
  }
  const std::uint64_t v = peek(ptr_);
  // MSB first, the first `len` bytes. Register MSB moved to bit 63 (size is
  // 2, 3 or 5), then fixed shifts: no per-byte variable shift loop.
  const std::uint64_t a = v << (64 - 8 * size);
  buf[0] = std::uint8_t(a >> 56);
  if (len > 1) buf[1] = std::uint8_t(a >> 48);
  if (len > 2) buf[2] = std::uint8_t(a >> 40);
  if (len > 3) buf[3] = std::uint8_t(a >> 32);
  if (len > 4) buf[4] = std::uint8_t(a >> 24);
  // Read side effects.
  if (ptr_ == DIAG_ALRT) {
    clearOnDiagRead();
  } else if (ptr_ == ENERGY) {
    diag_ &= ~ENERGYOF;
  } else if (ptr_ == CHARGE) {
    diag_ &= ~CHARGEOF;
  }
  return 0;
}

inline int Ina228Model::writeMsg(const std::uint8_t* buf, std::size_t len) noexcept {
  if (len == 0) {
    ++protocolErrors_;
    return EREMOTEIO;
  }
  const std::uint8_t reg = buf[0];
  const int size = regSize(reg);
  if (size == 0) {  // reserved pointer: not acknowledged
    ++protocolErrors_;
    return EREMOTEIO;
  }
  if (len == 1) {  // pointer only (a read follows)
    ptr_ = reg;
    return 0;
  }
  if (isReadOnly(reg) || len != std::size_t(1 + size)) {
    ++protocolErrors_;
    return EREMOTEIO;
  }
  ptr_ = reg;
  const std::uint16_t v = static_cast<std::uint16_t>((buf[1] << 8) | buf[2]);
  switch (reg) {
    case CONFIG:
      if (v & 0x8000) {  // RST: same as power-on, bit clears itself
        reset();
        return 0;
      }
      if (v & 0x4000) {  // RSTACC
        energyAcc_ = chargeAcc_ = 0.0;
        diag_ &= ~(ENERGYOF | CHARGEOF | MATHOF);
      }
      config_ = v & 0x3FF0;  // RST/RSTACC self-clear; bits 3:0 reserved
      codesValid_ = false;   // ADCRANGE sets the shunt LSB
      break;
    case ADC_CONFIG:
      adcConfig_ = v;
      restartConversions();
      break;
    case SHUNT_CAL:
      shuntCal_ = v & 0x7FFF;
      codesValid_ = false;  // the raw power code depends on it
      break;
    case SHUNT_TEMPCO:
      tempco_ = v & 0x3FFF;
      break;
    case DIAG_ALRT:
      // Only the four control bits are writable; the rest are status.
      diag_ = static_cast<std::uint16_t>((diag_ & 0x0FFF) | (v & 0xF000));
      limitActive_ = (diag_ & kLimitFlags) != 0;
      codesValid_ = false;  // SLOWALERT decides whether the raw power is needed
      break;
    case SOVL:
      sovl_ = v;
      break;
    case SUVL:
      suvl_ = v;
      break;
    case BOVL:
      bovl_ = v & 0x7FFF;
      break;
    case BUVL:
      buvl_ = v & 0x7FFF;
      break;
    case TEMP_LIMIT:
      tempLimit_ = v;
      break;
    case PWR_LIMIT:
      pwrLimit_ = v;
      break;
    default:
      break;
  }
  refreshLimits();      // any register write may move a limit or the active channels
  oneSampleUntil_ = 0;  // and the window, the codes or SLOWALERT: the next sample goes the full way
  return 0;
}

int Ina228Model::read(std::uint8_t* buf, std::size_t len) noexcept { return readMsg(buf, len); }
int Ina228Model::write(const std::uint8_t* buf, std::size_t len) noexcept { return writeMsg(buf, len); }

int Ina228Model::transact(TimeNs t, std::span<I2cMsg> msgs) noexcept {
  update(t);
  // The driver's poll, every control tick: pointer + read pairs for
  // DIAG_ALRT (2 bytes) and, when a result is due, VBUS and CURRENT (3
  // bytes each). Each such pair is done as its two messages would be
  // (pointer set, the register's bytes MSB first, DIAG_ALRT's read side
  // effect; VBUS and CURRENT have none), without the per-message checks and
  // dispatch; the first message that is not part of such a pair goes through
  // the general loop.
  I2cMsg* m = msgs.data();
  std::size_t n = msgs.size();
  while (n >= 2 && !m[0].read && m[0].len == 1 && m[0].buf != nullptr && m[1].read && m[1].buf != nullptr) {
    const std::uint8_t reg = m[0].buf[0];
    std::uint8_t* const b = m[1].buf;
    if (reg == DIAG_ALRT && m[1].len == 2) {
      readDiag(b);
    } else if ((reg == VBUS || reg == CURRENT) && m[1].len == 3) {
      const std::uint32_t v = reg20(reg == VBUS ? vbus_ : current_);
      b[0] = std::uint8_t(v >> 16);
      b[1] = std::uint8_t(v >> 8);
      b[2] = std::uint8_t(v);
    } else {
      break;
    }
    ptr_ = reg;
    m += 2;
    n -= 2;
  }
  return runMessages(
      std::span<I2cMsg>(m, n), [this](std::uint8_t* b, std::size_t len) { return readMsg(b, len); },
      [this](const std::uint8_t* b, std::size_t len) { return writeMsg(b, len); });
}

}  // namespace xr::sim

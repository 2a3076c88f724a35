#include "drivers/ads1115/ads1115_driver.h"

#include <cerrno>

#include "drivers/ads1115/ads1115_registers.h"
#include "drivers/frontend/analog_frontend.h"
#include "drivers/i2c/i2c_registers.h"

namespace xr {

namespace {
constexpr int kDefaultSequence[] = {1, 0, 1, 2, 1, 3};
// Shortest data period with the oscillator 10 % fast, minus a margin for the
// edge-to-ioctl path: all I2C work for one edge must finish inside it, or the
// result/MUX attribution becomes ambiguous.
constexpr TimeNs kEdgeBudget = Ads1115Driver::kPeriod * 9 / 10 - 100'000;
// An edge gap above this means at least one edge was missed (nominal period
// at most 1.1 T; a missed edge gives >= 1.8 T).
constexpr TimeNs kMissedEdgeGap = Ads1115Driver::kPeriod * 3 / 2;
// Same channel twice in a row: no MUX write, one period + 10 % for a new result.
constexpr TimeNs kSameChannelWait = Ads1115Driver::kPeriod * 11 / 10 + 20'000;
}  // namespace

Ads1115Driver::Ads1115Driver(I2cBus& bus, std::uint16_t address, std::span<const int> channelSequence,
                             const AnalogFrontEndSettings& frontend, const Clock& clock,
                             AdsPacing pacing) noexcept
    : bus_(bus),
      addr_(address),
      fe_(frontend),
      ch0Gain_(frontend::dividerGain(frontend)),
      rpmScale_(frontend::rpmScale(frontend)),
      clock_(clock),
      pacing_(pacing) {
  bool ok = !channelSequence.empty() && channelSequence.size() <= kMaxSequence;
  for (int c : channelSequence) ok = ok && c >= 0 && c <= 3;
  std::span<const int> use = ok ? channelSequence : std::span<const int>(kDefaultSequence);
  configError_ = !ok;
  edgePtr_ = ads1115::CONVERSION;
  edgeWrite_[0] = ads1115::CONFIG;
  edgeMsgs_[0] = {addr_, false, &edgePtr_, 1};
  edgeMsgs_[1] = {addr_, true, edgeRead_, 2};
  edgeMsgs_[2] = {addr_, false, edgeWrite_, 3};
  refreshEdgeConfigs();
  seqLen_ = use.size();
  for (std::size_t i = 0; i < seqLen_; ++i) seq_[i] = use[i];
}

void Ads1115Driver::setPga(int channel, unsigned pga) noexcept {
  if (channel >= 0 && channel <= 3) pga_[static_cast<std::size_t>(channel)] = pga & 7;
  refreshEdgeConfigs();
}

int Ads1115Driver::nextChannel() noexcept {
  // Wrap by compare, not `%` (a 64-bit division on every conversion);
  // seqPos_ < seqLen_ always holds.
  if (++seqPos_ >= seqLen_) seqPos_ = 0;
  return seq_[seqPos_];
}

std::uint16_t Ads1115Driver::configFor(int channel) const noexcept {
  const std::uint16_t c = ads1115::configContinuous(channel, pga_[static_cast<std::size_t>(channel)],
                                                    ads1115::DR_860, pacing_ == AdsPacing::ReadyEdge);
  return pacing_ == AdsPacing::SingleShot ? static_cast<std::uint16_t>(c | ads1115::MODE_SINGLE) : c;
}

int Ads1115Driver::writeMux(int channel) noexcept {
  // SingleShot: OS=1 starts the conversion with this MUX at once.
  const std::uint16_t cfg = pacing_ == AdsPacing::SingleShot
                                ? static_cast<std::uint16_t>(configFor(channel) | ads1115::OS)
                                : configFor(channel);
  const int rc = i2creg::writeReg16(bus_, addr_, ads1115::CONFIG, cfg);
  if (rc == 0) lastWritten_ = cfg;
  return rc;
}

int Ads1115Driver::readConversionChecked(std::uint16_t* raw) noexcept {
  std::uint8_t pCfg = ads1115::CONFIG, pConv = ads1115::CONVERSION;
  std::uint8_t cfg[2] = {}, conv[2] = {};
  I2cMsg msgs[4] = {
      {addr_, false, &pCfg, 1}, {addr_, true, cfg, 2}, {addr_, false, &pConv, 1}, {addr_, true, conv, 2}};
  const int rc = bus_.transfer(msgs);
  if (rc != 0) return rc;
  const std::uint16_t c = static_cast<std::uint16_t>((cfg[0] << 8) | cfg[1]);
  // OS (bit 15) is a busy flag when read: compare the rest.
  if ((c & 0x7FFF) != (lastWritten_ & 0x7FFF)) return ESTALE;
  *raw = static_cast<std::uint16_t>((conv[0] << 8) | conv[1]);
  return 0;
}

void Ads1115Driver::refreshEdgeConfigs() noexcept {
  for (int ch = 0; ch < 4; ++ch) {
    edgeConfig_[static_cast<std::size_t>(ch)] = configFor(ch);
    voltsPerCode_[static_cast<std::size_t>(ch)] = ads1115::voltsPerCode(pga_[static_cast<std::size_t>(ch)]);
  }
}

int Ads1115Driver::start(TimeNs now) noexcept {
  refreshEdgeConfigs();  // pacing_ may have changed (setPacing)
  seqPos_ = 0;
  const int first = seq_[0];
  int rc = 0;
  if (pacing_ == AdsPacing::ReadyEdge) {
    rc = i2creg::writeReg16(bus_, addr_, ads1115::HI_THRESH, ads1115::kReadyHiThresh);
    if (rc == 0) rc = i2creg::writeReg16(bus_, addr_, ads1115::LO_THRESH, ads1115::kReadyLoThresh);
  }
  if (rc == 0) rc = writeMux(first);
  // The ADS1115 has no ID register: read the Config back and compare every
  // field but OS (a busy flag) as the presence check.
  std::uint16_t back = 0;
  if (rc == 0) rc = i2creg::readReg16(bus_, addr_, ads1115::CONFIG, &back);
  const std::uint16_t want = configFor(first);
  if (rc == 0 && (back & 0x7FFF) != (want & 0x7FFF)) rc = ENODEV;
  if (rc != 0) {
    present_ = false;
    stats_.lastError = rc;
    nextRedetect_ = now + kRedetectInterval;
    return rc;
  }
  present_ = true;
  stats_.consecutiveFailures = 0;
  timedChannel_ = first;
  muxWrittenAt_ = clock_.now();
  // Continuous conversions start at the write with this config: the one in
  // progress and the next both use it.
  // Edge pacing: the conversion running at the write may use an older
  // Config (a restart while the chip kept converting): label nothing until
  // the pipeline refills.
  inProgress_ = -1;
  nextUp_ = -1;
  nextVerify_ = now + kVerifyInterval;
  missedAfter_ = kNoEdgeYet;
  return 0;
}

int Ads1115Driver::setPacing(AdsPacing pacing, TimeNs now) noexcept {
  pacing_ = pacing;
  const int rc = start(now);
  if (rc != 0) noteFailure(rc, now);
  return rc;
}

void Ads1115Driver::noteFailure(int err, TimeNs now) noexcept {
  ++stats_.failedReads;
  ++stats_.consecutiveFailures;
  stats_.lastError = err;
  if (stats_.consecutiveFailures >= kFailRunForRedetect) {
    present_ = false;
    nextRedetect_ = now + kRedetectInterval;
  }
}

inline void Ads1115Driver::accept(int channel, std::uint16_t raw, TimeNs stamp) noexcept {
  auto& s = samples_.ch[static_cast<std::size_t>(channel)];
  // ads1115::codeToVolts(raw, pga_[channel]) with the factor looked up once.
  const double v = static_cast<std::int16_t>(raw) * voltsPerCode_[static_cast<std::size_t>(channel)];
  s.adcVolts = v;
  switch (channel) {
    case 0:  // frontend::batteryVoltsFromAdc with the gain computed once
      s.value = v * ch0Gain_;
      break;
    case 1: {  // frontend::altAmpsFromAdc, the same expression, inlined
      const double a = (v - fe_.hall_zero_v) / fe_.hall_sensitivity_v_per_a;
      s.value = fe_.hall_invert ? -a : a;
      break;
    }
    case 2: {  // frontend::rpmFromAdc with the scale computed once
      const double rpm = v * rpmScale_;
      s.value = rpm < fe_.rpm_low_floor ? 0.0 : rpm;
      break;
    }
    default:
      // A pure function of the code (fe_ and the PGA are fixed): the log in
      // it is skipped while the thermistor reads the same code again.
      if (!ch3Cached_ || raw != ch3Raw_) {
        ch3Value_ = frontend::tempFFromAdc(fe_, v);
        ch3Raw_ = raw;
        ch3Cached_ = true;
      }
      s.value = ch3Value_;
      break;
  }
  s.stamp = stamp;
  s.fresh = true;
  ++s.count;
}

void Ads1115Driver::flushPipeline() noexcept {
  ++stats_.pipelineFlushes;
  inProgress_ = -1;
  nextUp_ = -1;
}

Ads1115Samples Ads1115Driver::poll(TimeNs now) noexcept {
  Ads1115Samples out = service(now);
  clearFresh();
  return out;
}

const Ads1115Samples& Ads1115Driver::serviceDue(TimeNs now) noexcept {
  if (!present_ && now >= nextRedetect_) {
    nextRedetect_ = now + kRedetectInterval;
    if (start(now) == 0) ++stats_.redetects;
  }
  if (present_ && pacing_ == AdsPacing::Timed && now - muxWrittenAt_ >= kSettle) {
    bool advance = true;
    if (timedChannel_ >= 0) {
      std::uint16_t raw = 0;
      const int rc = readConversionChecked(&raw);
      if (rc == ESTALE) {
        // The chip lost our Config (power glitch / hot-plug): restart it.
        ++stats_.reconfigures;
        ++stats_.discarded;
        if (start(now) != 0) noteFailure(stats_.lastError, now);
        advance = false;
      } else if (rc != 0) {
        noteFailure(rc, now);
        advance = false;  // keep the channel; read again next poll
      } else {
        stats_.consecutiveFailures = 0;
        accept(timedChannel_, raw, now);
      }
    }
    if (advance && present_) {
      const int next = nextChannel();
      if (next == timedChannel_) {
        // No MUX change: a new result after one period (+10 %).
        muxWrittenAt_ = now - (kSettle - kSameChannelWait);
      } else {
        const int rc = writeMux(next);
        // On a failed write the chip may hold either MUX: label nothing
        // until a write succeeds and a full settle time has passed.
        timedChannel_ = rc == 0 ? next : -1;
        muxWrittenAt_ = clock_.now();
        if (rc != 0) noteFailure(rc, now);
      }
    }
  }
  if (present_ && pacing_ == AdsPacing::SingleShot && now - muxWrittenAt_ >= kSingleShotWait) {
    pollSingleShot(now);
  }
  if (present_ && pacing_ == AdsPacing::ReadyEdge && now >= nextVerify_) {
    nextVerify_ = now + kVerifyInterval;
    std::uint16_t cfg = 0;
    const int rc = i2creg::readReg16(bus_, addr_, ads1115::CONFIG, &cfg);
    // Only a MUX-independent check is race-free here (the MUX changes every
    // edge): continuous mode, 860 SPS, comparator on.
    const std::uint16_t mask = ads1115::MODE_SINGLE | (7u << 5) | 3u;
    if (rc == 0 && (cfg & mask) != (configFor(seq_[0]) & mask)) {
      ++stats_.reconfigures;
      if (start(now) != 0) noteFailure(stats_.lastError, now);
    } else if (rc != 0) {
      noteFailure(rc, now);
    }
  }
  samples_.present = present_;
  return samples_;
}

void Ads1115Driver::pollSingleShot(TimeNs now) noexcept {
  std::uint8_t pCfg = ads1115::CONFIG, pConv = ads1115::CONVERSION;
  std::uint8_t cfg[2] = {}, conv[2] = {};
  I2cMsg msgs[4] = {
      {addr_, false, &pCfg, 1}, {addr_, true, cfg, 2}, {addr_, false, &pConv, 1}, {addr_, true, conv, 2}};
  int rc = bus_.transfer(msgs);
  if (rc != 0) {
    noteFailure(rc, now);
    // The conversion may or may not have been started: start one afresh.
    if (present_ && writeMux(seq_[seqPos_]) == 0) {
      timedChannel_ = seq_[seqPos_];
      muxWrittenAt_ = clock_.now();
    }
    return;
  }
  stats_.consecutiveFailures = 0;
  const std::uint16_t c = static_cast<std::uint16_t>((cfg[0] << 8) | cfg[1]);
  if ((c & 0x7FFF) != (lastWritten_ & 0x7FFF)) {
    // Reset chip (power glitch) or a foreign write: restart, label nothing.
    ++stats_.reconfigures;
    ++stats_.discarded;
    if (start(now) != 0) noteFailure(stats_.lastError, now);
    return;
  }
  if ((c & ads1115::OS) == 0) return;  // still converting (slow oscillator): next poll
  if (timedChannel_ >= 0) accept(timedChannel_, static_cast<std::uint16_t>((conv[0] << 8) | conv[1]), now);
  const int next = nextChannel();
  rc = writeMux(next);
  timedChannel_ = rc == 0 ? next : -1;
  muxWrittenAt_ = clock_.now();
  if (rc != 0) noteFailure(rc, now);
}

void Ads1115Driver::skipResultAndWriteMux(TimeNs edge, int c, std::uint16_t cfg) noexcept {
  // Which conversion the register holds is no longer certain: skip the
  // read, only write the MUX for the conversion after next.
  stats_.discarded += 1;
  flushPipeline();
  const int rc = bus_.transfer({&edgeMsgs_[2], 1});
  inProgress_ = nextUp_;
  if (rc != 0) {
    noteFailure(rc, edge);
    nextUp_ = -1;
    return;
  }
  lastWritten_ = cfg;
  nextUp_ = (clock_.now() - edge <= kEdgeBudget) ? c : -1;
}

void Ads1115Driver::onReadyEdge(TimeNs edge) noexcept {
  if (!present_ || pacing_ != AdsPacing::ReadyEdge) return;
  // edge - lastEdge > kMissedEdgeGap, with the bound added once per edge
  // (a stamp of 0 stands for "no edge yet", as start() leaves it).
  const bool missed = edge > missedAfter_;
  missedAfter_ = edge != 0 ? edge + kMissedEdgeGap : kNoEdgeYet;
  const bool late = clock_.now() - edge > kEdgeBudget;
  const std::size_t pos = seqPos_;
  const int c = nextChannel();
  const std::uint16_t cfg = edgeConfig_[static_cast<std::size_t>(c)];
  std::uint8_t* const wr = edgeWrite_;
  wr[1] = static_cast<std::uint8_t>(cfg >> 8);
  wr[2] = static_cast<std::uint8_t>(cfg & 0xFF);
  if (missed || late) {
    skipResultAndWriteMux(edge, c, cfg);
    return;
  }
  // The result of the conversion that just ended and the MUX for the
  // conversion after next in ONE combined transaction (pointer, read,
  // Config write; repeated starts, as the chip allows): the same register
  // accesses in the same order as two transfers, one ioctl on the board.
  // The messages are built once (constructor): only the Config bytes change.
  const int rc = bus_.transfer(edgeMsgs_);
  if (rc != 0) {
    // Which message failed is unknown: the result is not trusted and the
    // chip may hold either MUX. Flush (the next two results are discarded)
    // and keep the sequence where it was, as when the read alone failed.
    seqPos_ = pos;
    noteFailure(rc, edge);
    flushPipeline();
    return;
  }
  stats_.consecutiveFailures = 0;
  if (inProgress_ >= 0) {
    accept(inProgress_, static_cast<std::uint16_t>((edgeRead_[0] << 8) | edgeRead_[1]), edge);
  } else {
    ++stats_.discarded;
  }
  lastWritten_ = cfg;
  // The conversion that started at this edge uses the last config written
  // before it; the write must land before the next edge to label the next
  // conversion.
  inProgress_ = nextUp_;
  nextUp_ = (clock_.now() - edge <= kEdgeBudget) ? c : -1;
}

}  // namespace xr

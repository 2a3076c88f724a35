#pragma once
// ADS1115 driver (docs/install.md, wiring): continuous conversion at 860 SPS over a
// channel sequence that favours CH1 (default {1,0,1,2,1,3}, configurable).
// Each channel sample carries its value (scaled by drivers/frontend), the
// ADC volts, a timestamp and a freshness flag.
//
// The MUX rule (docs/sources.md D2.4): a Config write in continuous mode does
// not affect the conversion in progress; the first result with the new MUX
// is the one completing after the NEXT conversion start. Two pacings:
//  - Timed (no ALERT/RDY wired; also the simulator): after each MUX write a
//    result is trusted only once 2 data periods + 10 % (oscillator tolerance)
//    have passed since the write completed. One sample per settle time.
//  - ReadyEdge (ALERT/RDY on a GPIO, see AdsReadyLine in drivers/gpio/gpio_libgpiod.h): the
//    runtime calls onReadyEdge() for each edge; the driver reads the result
//    and writes the MUX for the conversion after next (a 2-deep pipeline),
//    so every conversion is used (~860 samples/s). A late write or a missed
//    edge makes the channel attribution ambiguous: the pipeline is flushed
//    (the next two results are discarded) rather than mislabel a channel.
//
// RT-safe: noexcept, no allocation, blocks only inside I2cBus::transfer().
// Not thread-safe: call from the control thread only.
#include <array>
#include <cstdint>
#include <limits>
#include <span>

#include "config/settings.h"
#include "core/inputs.h"
#include "core/time.h"
#include "drivers/hal/clock.h"
#include "drivers/hal/i2c_bus.h"

namespace xr {

// Timed: continuous, 2-period settle after each MUX write (~1 sample per
//   2.6 ms). SingleShot: one triggered 860 SPS conversion per poll, started
//   with its MUX so nothing is ambiguous, read once OS reports done (~1.3 ms
//   later): one sample per control tick, twice Timed's rate without an
//   ALERT/RDY line. ReadyEdge: continuous, pipelined on the RDY edges.
enum class AdsPacing { Timed, ReadyEdge, SingleShot };

struct AdsChannelSample {
  double adcVolts = kNoValue;  // volts at the ADS input
  double value = kNoValue;     // CH0 V, CH1 A (before DynamicAltCurrentZero), CH2 RPM, CH3 °F
  TimeNs stamp = 0;            // when the conversion result was read (0 = never)
  bool fresh = false;          // new since the previous poll()/takeSamples()
  std::uint32_t count = 0;     // results accepted since start
};

struct Ads1115Samples {
  std::array<AdsChannelSample, 4> ch{};
  bool present = false;
};

struct Ads1115Stats {
  unsigned long failedReads = 0;
  unsigned consecutiveFailures = 0;
  unsigned long discarded = 0;  // results dropped by the MUX rule / pipeline flushes
  unsigned long pipelineFlushes = 0;
  unsigned long redetects = 0;
  unsigned long reconfigures = 0;  // Config found reset/changed behind our back (power glitch) and restored
  int lastError = 0;
};

class Ads1115Driver {
 public:
  static constexpr std::size_t kMaxSequence = 16;
  static constexpr unsigned kFailRunForRedetect = 5;
  static constexpr TimeNs kRedetectInterval = 1'000'000'000;
  // Full-scale range per channel: PGA code 0 = ±6.144 V (the inputs may swing
  // to ~5 V on the upstream board; FSR never exceeds VDD+0.3 V in practice).
  static constexpr unsigned kDefaultPga = 0;

  // `channelSequence`: 1..16 entries, each 0..3; an invalid sequence falls
  // back to {1,0,1,2,1,3} and configError() reports it. `clock` timestamps
  // the completion of MUX writes (the settle time counts from then).
  Ads1115Driver(I2cBus& bus, std::uint16_t address, std::span<const int> channelSequence,
                const AnalogFrontEndSettings& frontend, const Clock& clock,
                AdsPacing pacing = AdsPacing::Timed) noexcept;

  // Not copyable: the ready-edge messages point into the driver itself.
  Ads1115Driver(const Ads1115Driver&) = delete;
  Ads1115Driver& operator=(const Ads1115Driver&) = delete;

  // Set a channel's PGA code before start() (default kDefaultPga).
  void setPga(int channel, unsigned pga) noexcept;
  // Writes thresholds (for ReadyEdge) and the Config for the first channel in
  // continuous mode, 860 SPS. Marks the chip present on success. 0 or errno.
  int start(TimeNs now) noexcept;

  // Timed pacing: reads/advances when the settle time has passed (each
  // result read together with the Config, see readConversionChecked). Both
  // pacings: once a second the Config is read back; a chip that reset is
  // restarted (stats().reconfigures). Both
  // pacings: returns every channel's latest sample with `fresh` set for those
  // updated since the previous poll(), then clears the fresh flags. While
  // absent, re-starts at most once per kRedetectInterval.
  Ads1115Samples poll(TimeNs now) noexcept;
  // poll() without the copy, for the per-tick path: the same work, then the
  // samples by reference with their fresh flags still set; clearFresh()
  // ends the tick's view (poll() == service() + copy + clearFresh()).
  // Inline: with edge pacing and no Config read-back due (all but one tick
  // a second) there is nothing to do but report presence.
  const Ads1115Samples& service(TimeNs now) noexcept {
    if (present_ && pacing_ == AdsPacing::ReadyEdge && now < nextVerify_) {
      samples_.present = true;
      return samples_;
    }
    return serviceDue(now);
  }
  void clearFresh() noexcept {
    for (auto& s : samples_.ch) s.fresh = false;
  }
  // ReadyEdge pacing: one call per ALERT/RDY edge, `edge` = its timestamp.
  void onReadyEdge(TimeNs edge) noexcept;
  // Change pacing at run time (e.g. ReadyEdge → SingleShot when no edges
  // arrive) and restart the chip with it. 0 or errno (as start()).
  int setPacing(AdsPacing pacing, TimeNs now) noexcept;

  bool present() const noexcept { return present_; }
  bool configError() const noexcept { return configError_; }
  const Ads1115Stats& stats() const noexcept { return stats_; }
  AdsPacing pacing() const noexcept { return pacing_; }
  std::span<const int> sequence() const noexcept { return {seq_.data(), seqLen_}; }
  // 2 data periods + 10 % + 20 µs: minimum wait after a MUX write (Timed).
  static constexpr TimeNs kSettle = (2 * 1'000'000'000LL / 860) * 11 / 10 + 20'000;
  // Nominal data period at 860 SPS.
  static constexpr TimeNs kPeriod = 1'000'000'000LL / 860;
  // SingleShot: one conversion (oscillator 10 % slow) + power-up, then read.
  static constexpr TimeNs kSingleShotWait = kPeriod * 11 / 10 + 45'000;

 private:
  const Ads1115Samples& serviceDue(TimeNs now) noexcept;
  int writeMux(int channel) noexcept;
  // Timed pacing: Config and Conversion in ONE combined transaction; the
  // result is trusted only when Config still holds what we wrote (a chip
  // that reset reads single-shot with a zero result). ESTALE on a mismatch.
  int readConversionChecked(std::uint16_t* raw) noexcept;
  std::uint16_t configFor(int channel) const noexcept;
  void pollSingleShot(TimeNs now) noexcept;
  void accept(int channel, std::uint16_t raw, TimeNs stamp) noexcept;
  // Ready edge that came late or after a missed one: no read, MUX write only.
  void skipResultAndWriteMux(TimeNs edge, int channel, std::uint16_t cfg) noexcept;
  void noteFailure(int err, TimeNs now) noexcept;
  void flushPipeline() noexcept;
  int nextChannel() noexcept;
  void refreshEdgeConfigs() noexcept;

  I2cBus& bus_;
  std::uint16_t addr_;
  AnalogFrontEndSettings fe_;
  // frontend::dividerGain / rpmScale of fe_, computed once (accept() runs
  // per conversion, ~860 times a second).
  double ch0Gain_;
  double rpmScale_;
  const Clock& clock_;
  AdsPacing pacing_;
  std::array<int, kMaxSequence> seq_{};
  std::size_t seqLen_ = 0;
  std::size_t seqPos_ = 0;
  std::array<unsigned, 4> pga_{kDefaultPga, kDefaultPga, kDefaultPga, kDefaultPga};
  bool configError_ = false;
  bool present_ = false;
  // Timed: channel whose MUX was written and when the write completed.
  int timedChannel_ = -1;
  TimeNs muxWrittenAt_ = 0;
  // ReadyEdge: channel of the conversion in progress, and of the next one.
  int inProgress_ = -1;
  int nextUp_ = -1;
  // Last edge + the missed-edge gap: a later edge means one was missed.
  static constexpr TimeNs kNoEdgeYet = std::numeric_limits<TimeNs>::max();
  TimeNs missedAfter_ = kNoEdgeYet;
  TimeNs nextRedetect_ = 0;
  TimeNs nextVerify_ = 0;
  std::uint16_t lastWritten_ = 0;  // last Config written successfully
  static constexpr TimeNs kVerifyInterval = 1'000'000'000;
  Ads1115Samples samples_;
  Ads1115Stats stats_;
  // Ready-edge path (~860 times a second), built once: configFor() per
  // channel (refreshed by start() and setPga()) and the combined
  // transaction's messages over these buffers (pointer to Conversion, the
  // result, the Config write).
  std::array<std::uint16_t, 4> edgeConfig_{};
  std::array<double, 4> voltsPerCode_{};  // ads1115::voltsPerCode(pga_[ch])
  std::uint8_t edgePtr_ = 0;              // ads1115::CONVERSION (set in the constructor)
  std::uint8_t edgeRead_[2] = {};
  std::uint8_t edgeWrite_[3] = {};  // ads1115::CONFIG, then the value
  I2cMsg edgeMsgs_[3] = {};
  // CH3 (thermistor) conversion of the last code: tempFFromAdc has a log.
  bool ch3Cached_ = false;
  std::uint16_t ch3Raw_ = 0;
  double ch3Value_ = 0.0;
};

}  // namespace xr

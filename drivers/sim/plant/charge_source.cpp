#include "drivers/sim/plant/charge_source.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace xr::sim {

namespace {
// The controller's voltage loop: amps per volt of error per second. With a
// bank of a few milliohms this settles in about a second, well inside any
// of the regulator's loops, and stays stable at the plant's steps.
constexpr double kLoopAPerVs = 60.0;
constexpr double kRebulkHoldS = 60.0;
constexpr double kTailHoldS = 30.0;
}  // namespace

std::string_view toString(SourceStage s) {
  switch (s) {
    case SourceStage::Off:
      return "off";
    case SourceStage::Bulk:
      return "bulk";
    case SourceStage::Absorption:
      return "absorption";
    case SourceStage::Float:
      return "float";
  }
  return "?";
}

ChargeSource::ChargeSource(const ChargeSourceConfig& c, double nominalV) : cfg_(c), on_(c.on) {
  const double k = nominalV / 12.0;
  if (!(cfg_.absorption_v > 0.0)) cfg_.absorption_v = 14.4 * k;
  if (!(cfg_.float_v > 0.0)) cfg_.float_v = 13.5 * k;
  if (!(cfg_.rebulk_v > 0.0)) cfg_.rebulk_v = 12.8 * k;
  if (!(cfg_.tail_a > 0.0)) cfg_.tail_a = 0.05 * cfg_.max_a;
}

double ChargeSource::availableAmps() const noexcept {
  if (!cfg_.present || !on_) return 0.0;
  if (!cfg_.solar) return cfg_.max_a;
  const double h = std::fmod(cfg_.start_h + t_ / 3600.0, 24.0);
  const double day = cfg_.sunset_h - cfg_.sunrise_h;
  if (h <= cfg_.sunrise_h || h >= cfg_.sunset_h || day <= 0.0) return 0.0;
  return cfg_.max_a * std::sin(std::numbers::pi * (h - cfg_.sunrise_h) / day);
}

void ChargeSource::step(double busV, double dt) noexcept {
  if (!cfg_.present) return;
  t_ += dt;
  const double avail = availableAmps();
  if (avail <= 0.0) {
    // Night, or shore power off: it starts again in bulk.
    stage_ = SourceStage::Off;
    amps_ = 0.0;
    return;
  }
  if (stage_ == SourceStage::Off) {
    stage_ = SourceStage::Bulk;
    stageS_ = 0.0;
    amps_ = 0.0;  // ramps up through its loop, as a controller soft-starts
  }
  stageS_ += dt;
  const double setV = stage_ == SourceStage::Float ? cfg_.float_v : cfg_.absorption_v;
  amps_ = std::clamp(amps_ + kLoopAPerVs * (setV - busV) * dt, 0.0, avail);
  switch (stage_) {
    case SourceStage::Bulk:
      if (busV >= setV - 0.05) stage_ = SourceStage::Absorption, stageS_ = 0.0, lowS_ = 0.0;
      break;
    case SourceStage::Absorption:
      // The tail counts only while it holds the voltage (not when the sun is weak).
      lowS_ = busV >= setV - 0.1 && amps_ < cfg_.tail_a ? lowS_ + dt : 0.0;
      if (lowS_ >= kTailHoldS || stageS_ >= cfg_.absorption_s)
        stage_ = SourceStage::Float, stageS_ = lowS_ = 0.0;
      break;
    case SourceStage::Float:
      lowS_ = busV < cfg_.rebulk_v ? lowS_ + dt : 0.0;
      if (lowS_ >= kRebulkHoldS) stage_ = SourceStage::Bulk, stageS_ = 0.0, lowS_ = 0.0;
      break;
    case SourceStage::Off:
      break;
  }
}

}  // namespace xr::sim

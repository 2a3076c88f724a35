#pragma once
// BeltSlipDetector: a slipping alternator belt, one event per episode
// (docs/operations.md "Belt slip"). Two signs, on one-second means:
//   A. The tach (the alternator's own speed) against the engine's speed
//      from NMEA 2000: their ratio, learned while the belt grips, falls by
//      kSlipShare or more for kHoldS with the engine steady.
//   B. At a steady speed, the current falls while the duty rises and the
//      regulator still wants more: the field is pushed and the machine
//      gives less, as when its pulley slows under the belt.
// Ordinary speed changes meet neither: A needs the engine steady, and B a
// steady speed. Pure: no clock, no I/O.
#include <array>

#include "core/events.h"
#include "core/inputs.h"

namespace xr {

namespace belt_k {
inline constexpr int kWindowS = 20;           // B's window; A's steadiness is judged over kHoldS
inline constexpr int kHoldS = 10;             // A: seconds the ratio stays low
inline constexpr double kSlipShare = 0.05;    // A: the ratio this far below its learned value
inline constexpr double kLearnTauS = 600.0;   // A: how slowly the learned ratio follows
inline constexpr int kLearnFirstS = 30;       // A: seconds before a ratio is trusted
inline constexpr double kSteadyShare = 0.03;  // speed within this of its mean
inline constexpr double kMinRpm = 500.0;      // slower than this, neither sign is read
inline constexpr double kDutyRise = 10.0;     // B: duty points
inline constexpr double kCurrentDropA = 5.0, kCurrentDropShare = 0.10;  // B
inline constexpr double kWantMoreA = 5.0;                               // B: target above the current by this
inline constexpr double kRearmS = 600.0;                                // quiet seconds before a new episode
inline constexpr double kFreshS = 2.0;  // an engine speed older than this is not read
}  // namespace belt_k

struct BeltSample {
  double rpm = kNoValue;        // the RPM input (tach, or the engine's for RpmSource = n2k)
  double engineRpm = kNoValue;  // the engine's speed from NMEA 2000, when heard and fresh
  double altAmps = kNoValue;
  double dutyPct = 0.0;
  double targetAmps = kNoValue;  // what the current loop asks for
  bool fieldOn = false;
};

class BeltSlipDetector {
 public:
  // Every tick. Returns true (and pushes BeltSlip) when an episode begins.
  bool update(TimeNs now, double dt_s, const BeltSample& s, EventBatch& ev) noexcept;
  bool slipping() const noexcept { return latched_; }
  double learnedRatio() const noexcept { return ratio_; }

 private:
  struct Second {
    double rpm = 0.0, engine = 0.0, amps = 0.0, duty = 0.0, target = 0.0;
    bool field = false, engineKnown = false;
  };
  bool closeSecond(TimeNs now, EventBatch& ev) noexcept;
  bool ratioSign(const Second& s, double& slipPct) noexcept;
  bool currentSign(double& dropA, double& riseDuty) const noexcept;
  const Second& ago(int s) const noexcept {
    return ring_[(next_ + belt_k::kWindowS - 1 - s) % belt_k::kWindowS];
  }
  std::array<Second, belt_k::kWindowS> ring_{};
  int next_ = 0, filled_ = 0;
  Second acc_{};
  double accT_ = 0.0;
  int engineSeconds_ = 0;  // seconds the engine speed was heard in this bucket
  double ratio_ = 0.0;     // learned tach / engine (0 = not yet)
  int learnS_ = 0;
  double learnSum_ = 0.0;
  int lowS_ = 0;  // consecutive seconds of a low ratio
  bool latched_ = false;
  double quietS_ = 0.0;
};

}  // namespace xr

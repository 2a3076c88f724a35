#pragma once
// BeltSlipDetector: a slipping alternator belt, one event per episode
// (docs/operations.md "Belt slip"). Two signs, on one-second means:
//   A. The tach (the alternator's own speed) against the engine's speed
//      from NMEA 2000: their ratio, learned while the belt grips, falls by
//      kSlipShare or more for kHoldS with the engine steady.
//   B. At a steady speed, the current falls while the duty rises and the
//      regulator still wants more: the field is pushed and the machine
//      gives less, as when its pulley slows under the belt.
//   C. With the tach alone (no engine speed), a short probe: when the tach
//      falls fast while the alternator carries much of its rating, the
//      current target is held low for kProbeS. A slipping belt slips with
//      its load, so the alternator speeds up as the current falls, and
//      slows again when the current comes back; an engine that slowed does
//      neither. Lowering the field is always safe (less charge, never
//      more), and costs a few seconds of charge. Its BeltSlip event has
//      detail 3: a = the speed's rise (%), b = the current before the probe (A).
// Ordinary speed changes meet none: A needs the engine steady, B a steady
// speed, and C a speed that follows the current both ways. Pure: no clock,
// no I/O.
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
// C: the probe (tach alone).
inline constexpr int kFallWindowS = 5;             // the tach fell within this many seconds
inline constexpr double kFallShare = 0.08;         // by this share of its speed
inline constexpr double kProbeLoadShare = 0.4;     // while the current was this share of MaxTableValue
inline constexpr double kProbeMinA = 10.0;         // and at least this
inline constexpr double kProbeCapShare = 0.3;      // the target during the probe, a share of that current
inline constexpr int kProbeS = 6;                  // the probe's length
inline constexpr int kReleaseS = 6;                // watching the speed after it
inline constexpr double kProbeRiseShare = 0.04;    // the speed rises this share during the probe
inline constexpr double kProbeCurrentShare = 0.3;  // while the current falls by this share
inline constexpr double kProbeRearmS = 300.0;      // at most one probe in this many seconds
}  // namespace belt_k

struct BeltSample {
  double rpm = kNoValue;        // the RPM input (tach, or the engine's for RpmSource = n2k)
  double engineRpm = kNoValue;  // the engine's speed from NMEA 2000, when heard and fresh
  double altAmps = kNoValue;
  double dutyPct = 0.0;
  double targetAmps = kNoValue;  // what the current loop asks for
  bool fieldOn = false;
  bool engineHeard = false;  // an engine speed from NMEA 2000 at all (then sign A, no probe)
  double ratedA = 0.0;       // MaxTableValue: what "much of its rating" means for C
};

class BeltSlipDetector {
 public:
  // Every tick. Returns true (and pushes BeltSlip) when an episode begins.
  bool update(TimeNs now, double dt_s, const BeltSample& s, EventBatch& ev) noexcept;
  bool slipping() const noexcept { return latched_; }
  // C: the current target's ceiling while a probe runs (+infinity otherwise).
  double probeCapA() const noexcept { return probe_ == Probe::Holding ? probeCap_ : 1e300; }
  bool probing() const noexcept { return probe_ != Probe::Idle; }

 private:
  struct Second {
    double rpm = 0.0, engine = 0.0, amps = 0.0, duty = 0.0, target = 0.0;
    bool field = false, engineKnown = false;
  };
  bool closeSecond(TimeNs now, EventBatch& ev) noexcept;
  bool ratioSign(const Second& s, double& slipPct) noexcept;
  bool currentSign(double& dropA, double& riseDuty) const noexcept;
  bool probeSign(double& risePct, double& ampsBefore) noexcept;  // C (belt_slip_probe.cpp)
  enum class Probe { Idle, Holding, Releasing };
  Probe probe_ = Probe::Idle;
  int probeS_ = 0;
  double probeCap_ = 1e300, sinceProbeS_ = 1e9;
  double beforeRpm_ = 0.0, beforeAmps_ = 0.0, heldRpm_ = 0.0, heldAmps_ = 0.0;
  double ratedA_ = 0.0;
  bool engineHeard_ = false;
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

#pragma once
// FastOvEpisode: the control side of one fast over-voltage episode (the
// supervisors themselves are protection's, docs/protections.md "Fast
// over-voltage"): the cap of this tick, what the bank accepted when a load
// dump first acted, the clearing edge that reseeds the voltage loop, and the
// CV overshoot latch that bypasses the governor's slew.
#include "control/control_sensors.h"

namespace xr {

// What the episode reads each tick (AUTO).
struct EpisodeInputs {
  FastOvVerdict ov;                // the supervisors' verdict
  bool bcurSlowPrimed = false;     // the slow battery-current filter has a value
  double bcurSlowA = 0.0;          // battery current over seconds (before the dump)
  double Bcur = kNoValue;          // battery current now
  double measuredAmps = kNoValue;  // alternator current now (last fresh CH1)
};

// What the clearing edge asks of the other parts.
struct EpisodeOutcome {
  bool cleared = false;         // the clamp released this tick: the fast-rise window opens
  bool reseed = false;          // reseed the voltage loop (after a load dump)
  double reseedAtA = kNoValue;  // ... at this current (NaN: the bumpless reseed)
};

class FastOvEpisode {
 public:
  EpisodeOutcome update(const EpisodeInputs& in) noexcept;
  // CV overshoot latch: set when fast-OV fires in CV, released once IBV is
  // back under target + CV_OVERSHOOT_RELEASE_V (hysteresis stops chatter as
  // the field collapses). Returns the latch.
  bool updateOvershootLatch(bool voltageControlActive, double IBV, double target) noexcept;
  void clearOvershootLatch() noexcept { cvOvershootBypass_ = false; }

  bool clampActive() const noexcept { return clampActive_; }
  double capA() const noexcept { return capA_; }
  bool overshootBypass() const noexcept { return cvOvershootBypass_; }

 private:
  bool clampActive_ = false;        // a supervisor clamps the command this tick
  bool wasActive_ = false;          // ... and did last tick (the clearing edge)
  bool loadDumpInEpisode_ = false;  // a load dump acted since the clamp engaged
  double dumpAcceptA_ = kNoValue;   // the slow battery current when this episode's dump first acted
  double capA_ = 1e300;             // the supervisors' cap this tick
  bool cvOvershootBypass_ = false;  // the CV overshoot latch (governor slew bypassed)
};

}  // namespace xr

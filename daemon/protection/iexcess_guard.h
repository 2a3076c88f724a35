#pragma once
// IExcessGuard: Group 3 of the fast over-voltage supervisors
// (docs/protections.md "Group 3 — iExcess"): alternator current above the
// slewed setpoint + IExcessK for IExcessN ticks near the voltage target
// caps the request and snaps, bleeds or (on release) reseeds the CV
// integrator. Its signal (IExcessSigSrc) is the mean of the last IExcessMA_N
// fresh samples, the filtered or the raw current.
#include <array>

#include "core/fast_ov_verdict.h"
#include "core/time.h"
#include "params/params.h"

namespace xr {

struct FastOvInputs;

// What Group 3 decided this tick.
struct IExcessResult {
  bool active = false;                    // Group 3 acts (group3)
  double cap = 0.0;                       // its cap on the request (+infinity when inactive)
  CvIAction cvIAction = CvIAction::None;  // what to do with cv_I
  double cv_I = 0.0;                      // the new cv_I when cvIAction != None
};

// The rest of Group 3's view of the tick, besides the control values.
struct IExcessContext {
  double IBV = 0.0;          // INA228 bus voltage
  bool fastOvActed = false;  // Group 1, Group 2 or the load dump acted this tick
  double base = 0.0;         // fastOvBaseCap: the request before the clamp
  TimeNs now = 0;            // this tick
  TimeNs prevCall = -1;      // the previous supervisor call (the bleed's dt), -1 = none
};

class IExcessGuard {
 public:
  // One fresh alternator-current sample into the moving-average window.
  void push(const FastOvInputs& x) noexcept;
  IExcessResult update(const FastOvInputs& x, const IExcessContext& c, const Params& p) noexcept;
  void reset() noexcept;

 private:
  double signal(const FastOvInputs& x, const Params& p) const noexcept;

  std::array<double, 64> window_{};  // the last fresh MeasuredAmps samples (ring)
  int count_ = 0;                    // samples in the window
  int head_ = 0;                     // next slot to write
  int over_ = 0;                     // consecutive ticks over the threshold
  bool active_ = false;              // Group 3 acts
  double preEventCvI_ = 0.0;         // cv_I when it fired (the reseed's base)
  bool postFastOvGate_ = false;      // after Group 1/2/load dump: wait for the current to come back
};

}  // namespace xr

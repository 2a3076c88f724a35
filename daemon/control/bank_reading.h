#pragma once
// BankReading (docs/configuration.md "Not set up"): nobody has said which
// bank this is, so the bank class comes from the battery itself, read
// before any voltage trip is armed. Until the first battery-voltage reading
// (or kBankReadingWait without one) the field stays off; then the class of
// that reading is used. A reading that fits no class (18 V, 0 V, none within
// the wait) gives the 12 V class: the smallest limits, so the safe side, and
// the telemetry says it did not fit.
#include <optional>

#include "control/telemetry.h"
#include "core/inputs.h"
#include "params/derived.h"

namespace xr {

class BankReading {
 public:
  // Long enough for the INA228's slow (field-off) averaging to deliver its
  // first result (~1 s), short enough that a missing chip is reported by the
  // sensor checks soon after start.
  static constexpr TimeNs kWait = 5'000'000'000;

  // Each tick while the set-up asks for it: nothing while waiting, then the
  // class to scale the limits to (once; restart() reads again).
  std::optional<SystemClass> update(const Reading& ibv, TimeNs now) noexcept;
  // A new parameter set reads the bank again when it asks to.
  void restart() noexcept {
    shown_ = {};
    waiting_ = false;
  }
  // What the screens show of it (Telemetry::setupBank).
  const Telemetry::SetupBank& shown() const noexcept { return shown_; }

 private:
  bool waiting_ = false;        // a reading is awaited since since_
  TimeNs since_ = 0;            // the first tick that waited
  Telemetry::SetupBank shown_;  // the class read, for the screens
};

}  // namespace xr

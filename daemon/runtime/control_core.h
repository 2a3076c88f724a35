#pragma once
// What the control cycle drives: the pure core behind a small interface, so
// the runtime is tested with a scripted core and runs the real Regulator in
// the daemon (RegulatorCore in regulator_core.h).
#include "battery/ledger.h"
#include "control/outputs.h"
#include "core/commands.h"
#include "core/inputs.h"
#include "params/params.h"

namespace xr::rt {

class ControlCore {
 public:
  virtual ~ControlCore() = default;
  virtual const Outputs& step(const Inputs& in) = 0;
  virtual void setParams(const Params& p) = 0;
  virtual bool command(const Command& c) = 0;
  // The persistent battery state, for the store (copied out periodically).
  // False when the core has none.
  virtual bool ledger(BatteryLedger&) { return false; }
};

}  // namespace xr::rt

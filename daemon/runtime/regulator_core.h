#pragma once
// The real pure core behind the runtime's ControlCore seam (the daemon and
// the simulator rig's headless runner share it).
#include "control/regulator.h"
#include "runtime/control_core.h"

namespace xr::rt {

class RegulatorCore final : public ControlCore {
 public:
  explicit RegulatorCore(Regulator& r) : r_(r) {}
  const Outputs& step(const Inputs& in) override { return r_.step(in); }
  void setParams(const Params& p) override { r_.setParams(p); }
  bool command(const Command& c) override { return r_.command(c); }
  bool ledger(BatteryLedger& out) override {
    out = r_.ledger();
    return true;
  }

 private:
  Regulator& r_;
};

}  // namespace xr::rt

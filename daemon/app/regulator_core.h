#pragma once
// The real pure core behind the runtime's ControlCore seam.
#include "control/regulator.h"
#include "runtime/control_core.h"

namespace xr::app {

class RegulatorCore final : public rt::ControlCore {
 public:
  explicit RegulatorCore(Regulator& r) : r_(r) {}
  const Outputs& step(const Inputs& in) override { return r_.step(in); }
  void setParams(const Params& p) override { r_.setParams(p); }
  bool command(const Command& c) override { return r_.command(c); }
  const Outputs& completeTelemetry() override { return r_.completeTelemetry(); }
  bool ledger(BatteryLedger& out) override {
    out = r_.ledger();
    return true;
  }

 private:
  Regulator& r_;
};

}  // namespace xr::app

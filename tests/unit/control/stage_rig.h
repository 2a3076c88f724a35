#pragma once
// The charging-stage machine on its own, stepped at 100 ms: a 12 V bank in
// BULK at 13.0 V and 40 A, with helpers that take it to ABSORPTION and FLOAT.
#include <gtest/gtest.h>

#include <cmath>

#include "control/charging_stage.h"

namespace xr::test {

struct StageRig {
  Params p;
  ChargingStageMachine m;
  StageInputs in;
  StageRig() {
    p.BulkVoltage = 14.5;
    p.AbsorptionVoltage = 14.4;
    p.FloatVoltage = 13.5;
    p.RebulkVoltage = 12.9;
    in.now = fromSec(1000.0);
    in.v = 13.0;
    in.Bcur = 40.0;
    in.uTargetAmps = 50.0;
    m.resetToBulk(in.now);
  }
  // Steps of 100 ms for `seconds`; returns true if the stage changed.
  bool run(double seconds) {
    bool changed = false;
    const long n = std::lround(seconds / 0.1);
    for (long i = 0; i < n; ++i) {
      in.now += fromMs(100);
      changed |= m.updateChargingStage(in, p);
    }
    return changed;
  }
  void toAbsorption() {
    in.v = 14.5;
    run(p.bulkVoltageHoldMs / 1000.0 + 0.2);
    ASSERT_EQ(m.stage(), ChargeStage::ABSORPTION);
  }
  void toFloat() {
    toAbsorption();
    in.Bcur = 1.0;
    run(p.absorptionCompleteTime / 1000.0 + 0.2);
    ASSERT_EQ(m.stage(), ChargeStage::FLOAT);
    in.v = 13.5;
  }
};

}  // namespace xr::test

// VoltageTarget on its own (docs/control.md "Charging stages", "Override
// modes"): the bulk ceiling engages the voltage loop at BulkVoltage, not
// just under it, and lets go BULK_V_BAND_EXIT under it; the BMS's CVL caps
// every target; the not-set-up ceiling too.
#include "control/voltage_target.h"

#include <gtest/gtest.h>

#include "params/constants.h"

namespace xr {
namespace {

TargetInputs bulkAt(double v, TimeNs now) {
  TargetInputs in;
  in.now = now;
  in.IBV = v;
  in.Bcur = 30.0;
  in.uTargetAmps = 60.0;
  in.setpointCommand = 60.0;
  in.autoMode = true;
  return in;
}

TEST(VoltageTargetPart, BulkCeilingEngagesAtBulkVoltageNotBelow) {
  Params p;
  VoltageTarget t(p);
  EventBatch ev;
  t.update(bulkAt(p.BulkVoltage - 0.01, fromSec(1.0)), p, ev);
  ASSERT_TRUE(t.stages().inBulkStage());
  EXPECT_FALSE(t.voltageControlActive());
  t.update(bulkAt(p.BulkVoltage, fromSec(1.1)), p, ev);
  EXPECT_TRUE(t.bulkVoltageLimitActive());
  EXPECT_TRUE(t.voltageControlActive());
  t.update(bulkAt(p.BulkVoltage - k::BULK_V_BAND_EXIT + 0.005, fromSec(1.2)), p, ev);
  EXPECT_TRUE(t.voltageControlActive());  // inside the band: held
  t.update(bulkAt(p.BulkVoltage - k::BULK_V_BAND_EXIT - 0.005, fromSec(1.3)), p, ev);
  EXPECT_FALSE(t.bulkVoltageLimitActive());
  EXPECT_FALSE(t.voltageControlActive());
}

TEST(VoltageTargetPart, TheBmsCvlAndTheSetupCeilingCapTheTarget) {
  Params p;
  VoltageTarget t(p);
  EventBatch ev;
  TargetInputs in = bulkAt(13.0, fromSec(1.0));
  in.bmsCvlV = p.BulkVoltage - 0.3;
  t.update(in, p, ev);
  EXPECT_DOUBLE_EQ(t.ChargingVoltageTarget(), p.BulkVoltage - 0.3);
  EXPECT_TRUE(t.voltageControlActive());  // the loop runs under the CVL from the start
  in.bmsCvlV = kNoValue;
  p.SetupCeilingV = 13.8;
  t.update(in, p, ev);
  EXPECT_DOUBLE_EQ(t.ChargingVoltageTarget(), 13.8);
}

TEST(VoltageTargetPart, MaintainModeHoldsTheBulkTargetInCv) {
  Params p;
  p.MaintainMode = true;
  VoltageTarget t(p);
  EventBatch ev;
  t.update(bulkAt(13.0, fromSec(1.0)), p, ev);
  EXPECT_TRUE(t.voltageControlActive());
  EXPECT_DOUBLE_EQ(t.ChargingVoltageTarget(), p.BulkVoltage);
}

}  // namespace
}  // namespace xr

// AlarmPanel on its own: a row above its threshold sounds, at it does not;
// the 250 ms cadence; AlarmActivate gates every row but TempTaskHung; the
// latch and its reset; the acknowledgement.
#include <gtest/gtest.h>

#include "params/constants.h"
#include "params/derived.h"
#include "part_log.h"
#include "protection/alarms.h"

namespace xr::test {
namespace {

struct PanelRig {
  Params p;
  AlarmPanel panel;
  PartLog log;
  AlarmInput in;
  PanelRig() {
    in.TempToUse = 100.0;
    in.IBV = 13.5;
    in.MeasuredAmps = 20.0;
    in.Bcur = 10.0;
  }
  bool check(TimeNs dt = fromMs(k::ALARM_CHECK_MS)) {
    log.t += dt;
    const bool b = panel.update(in, p, log.at());
    log.collect();
    return b;
  }
};

TEST(AlarmPanelPart, VoltageHighSoundsAboveItsThresholdNotAtIt) {
  PanelRig r;
  r.in.IBV = voltageAlarmHighV(r.p);
  EXPECT_FALSE(r.check());
  r.in.IBV += 0.01;
  EXPECT_TRUE(r.check());
  EXPECT_EQ(r.log.count(EventCode::AlarmOn), 1u);
  EXPECT_EQ(r.log.count(EventCode::AlarmCondition), 1u);
}

TEST(AlarmPanelPart, EvaluatesEvery250msAndHoldsBetween) {
  PanelRig r;
  r.check();
  r.in.MeasuredAmps = currentAlarmHighAmps(r.p) + 1.0;
  EXPECT_FALSE(r.check(fromMs(k::ALARM_CHECK_MS) - fromMs(5)));  // not due yet
  EXPECT_TRUE(r.check(fromMs(5)));
}

TEST(AlarmPanelPart, AlarmActivateGatesEveryRowButTheTempTaskHang) {
  PanelRig r;
  r.p.AlarmActivate = false;
  r.in.IBV = voltageAlarmHighV(r.p) + 1.0;
  EXPECT_FALSE(r.check());
  r.in.tempTaskHung = true;
  EXPECT_TRUE(r.check());
}

TEST(AlarmPanelPart, LatchHoldsUntilResetAndAcknowledgeQuietsTheRowsSounding) {
  PanelRig r;
  r.p.AlarmLatchEnabled = true;
  r.in.faultMode = true;
  EXPECT_TRUE(r.check());
  r.in.faultMode = false;
  EXPECT_TRUE(r.check());  // latched
  r.panel.resetLatch();
  EXPECT_FALSE(r.check());
  r.in.faultMode = true;
  EXPECT_TRUE(r.check());
  r.panel.acknowledge(r.log.t);
  EXPECT_FALSE(r.check(fromMs(5)));         // quiet at the next tick
  r.in.IBV = voltageAlarmHighV(r.p) + 1.0;  // a new row sounds again
  EXPECT_TRUE(r.check());
}

}  // namespace
}  // namespace xr::test

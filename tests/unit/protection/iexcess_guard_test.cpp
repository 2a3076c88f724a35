// IExcessGuard (Group 3) on its own: fires after IExcessN ticks over
// setpointLimited + IExcessK near the target, not just below it, snaps or
// bleeds cv_I, reseeds on release, and its reset empties the window.
#include "protection/iexcess_guard.h"

#include <gtest/gtest.h>

#include <cmath>

#include "protection/fast_ov.h"

namespace xr::test {
namespace {

struct GuardRig {
  Params p;
  IExcessGuard guard;
  FastOvInputs x;
  IExcessContext c;
  GuardRig() {
    x.ChargingVoltageTarget = 14.4;
    x.setpointLimited = 40.0;
    x.cv_I = 30.0;
    x.altCurrentFresh = true;
    c.IBV = 14.4;
    c.base = 40.0;
    c.now = fromSec(100.0);
  }
  IExcessResult tick(double amps) {
    c.prevCall = c.now;
    c.now += fromMs(5);
    x.MeasuredAmps = amps;
    guard.push(x);
    return guard.update(x, c, p);
  }
};

TEST(IExcessGuardPart, FiresAfterNTicksOverTheThresholdAndSnapsCvI) {
  GuardRig r;
  const double over = r.x.setpointLimited + r.p.IExcessK + 1.0;
  IExcessResult res;
  for (int i = 0; i < r.p.IExcessN + 10; ++i) res = r.tick(over);  // fill the MA window
  EXPECT_TRUE(res.active);
  EXPECT_LT(res.cap, r.c.base);
  GuardRig fresh;
  for (int i = 0; i < 8; ++i) fresh.tick(fresh.x.setpointLimited);  // window full, below
  for (int i = 0; i < fresh.p.IExcessN - 1; ++i) EXPECT_FALSE(fresh.tick(1000.0).active);
  const IExcessResult fire = fresh.tick(1000.0);
  EXPECT_TRUE(fire.active);
  EXPECT_EQ(fire.cvIAction, CvIAction::Snap);
  EXPECT_DOUBLE_EQ(fire.cv_I, 0.0);
}

TEST(IExcessGuardPart, JustBelowTheThresholdNeverFires) {
  GuardRig r;
  for (int i = 0; i < 200; ++i) EXPECT_FALSE(r.tick(r.x.setpointLimited + r.p.IExcessK - 0.01).active);
}

TEST(IExcessGuardPart, ReleaseReseedsFromThePreEventIntegrator) {
  GuardRig r;
  for (int i = 0; i < 20; ++i) r.tick(r.x.setpointLimited + r.p.IExcessK + 10.0);
  IExcessResult res;
  for (int i = 0; i < 20 && res.cvIAction != CvIAction::Reseed; ++i) res = r.tick(0.0);
  EXPECT_EQ(res.cvIAction, CvIAction::Reseed);
  EXPECT_DOUBLE_EQ(res.cv_I, 30.0 * r.p.IExcessReseedFrac);
  EXPECT_FALSE(res.active);
}

TEST(IExcessGuardPart, BleedsWhenKBleedIsSetAndResetEmptiesTheWindow) {
  GuardRig r;
  r.p.IExcessKBleed = 0.5;
  IExcessResult res;
  for (int i = 0; i < 20; ++i) res = r.tick(r.x.setpointLimited + r.p.IExcessK + 10.0);
  EXPECT_EQ(res.cvIAction, CvIAction::Bleed);
  EXPECT_LT(res.cv_I, r.x.cv_I);
  EXPECT_GT(res.cv_I, 0.0);
  r.guard.reset();
  r.x.altCurrentFresh = false;  // no sample: the empty window gives no signal
  EXPECT_FALSE(r.guard.update(r.x, r.c, r.p).active);
}

TEST(IExcessGuardPart, WaitsAfterAFasterSupervisorActed) {
  GuardRig r;
  r.c.fastOvActed = true;
  r.tick(r.x.setpointLimited);
  r.c.fastOvActed = false;
  for (int i = 0; i < 20; ++i) EXPECT_FALSE(r.tick(r.x.setpointLimited + r.p.IExcessK + 10.0).active);
}

}  // namespace
}  // namespace xr::test

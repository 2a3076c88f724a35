// RpmGate on its own: the gate at MinRPMForField and just below it, an
// unknown RPM, IgnoreRPM, and the field rest's hold and grace.
#include "protection/rpm_gate.h"

#include <gtest/gtest.h>

#include <cmath>

#include "params/constants.h"
#include "part_log.h"

namespace xr::test {
namespace {

struct GateRig {
  Params p;
  RpmGate gate;
  PartLog log;
  void tick(double rpm, bool resting = false, TimeNs dt = fromMs(5)) {
    log.t += dt;
    gate.update({rpm, resting}, p, log.at());
    log.collect();
  }
};

TEST(RpmGatePart, OpenAtMinRpmClosedJustBelow) {
  GateRig r;
  r.tick(r.p.MinRPMForField);
  EXPECT_FALSE(r.gate.belowMin());
  r.tick(r.p.MinRPMForField - 1.0);
  EXPECT_TRUE(r.gate.belowMin());
  EXPECT_EQ(r.log.count(EventCode::ProtectionTrip, Reason::REASON_RPM_LOW), 1u);
}

TEST(RpmGatePart, UnknownRpmHoldsTheFieldOffWithoutATripUntilARealReading) {
  GateRig r;
  r.tick(NAN);
  EXPECT_TRUE(r.gate.belowMin());
  EXPECT_EQ(r.log.count(EventCode::ProtectionTrip), 0u);
  r.p.IgnoreRPM = true;
  r.tick(NAN);
  EXPECT_FALSE(r.gate.belowMin());
}

TEST(RpmGatePart, FieldRestTrustsTheRpmSeenBeforeItForTheGrace) {
  GateRig r;
  r.tick(1500.0);
  r.tick(0.0, true);  // the rest quiets a stator tach
  EXPECT_FALSE(r.gate.belowMin());
  r.tick(0.0, false);  // the rest ends: the grace starts
  r.tick(0.0, false, fromMs(k::RPM_REST_GRACE_MS) - fromMs(10));
  EXPECT_FALSE(r.gate.belowMin());
  r.tick(0.0, false, fromMs(20));
  EXPECT_TRUE(r.gate.belowMin());
}

}  // namespace
}  // namespace xr::test

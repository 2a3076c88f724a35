// InputFilters on its own (docs/control.md "Feedback filters"): the control
// dt counts only fresh CH1 samples and a stall is clipped at the limit (not
// integrated whole); the PID's signal follows OutputPIDSigSrc; the IBV slope
// is taken between fresh samples only.
#include "control/input_filters.h"

#include <gtest/gtest.h>

namespace xr {
namespace {

ControlSensors sample(TimeNs now, double amps, bool fresh = true) {
  ControlSensors s;
  s.now = now;
  s.ch1Fresh = fresh;
  s.MeasuredAmps = amps;
  return s;
}

TEST(InputFiltersPart, ControlDtOnFreshSamplesAndAStallIsClipped) {
  Params p;
  InputFilters f;
  f.update(sample(fromSec(1.0), 10.0), p);
  EXPECT_DOUBLE_EQ(f.controlDt(), 0.0);  // the first sample has no dt
  f.update(sample(fromSec(1.05), 10.0, false), p);
  EXPECT_DOUBLE_EQ(f.controlDt(), 0.0);  // not fresh: nothing to integrate
  f.update(sample(fromSec(1.1), 10.0), p);
  EXPECT_NEAR(f.controlDt(), 0.1, 1e-12);
  const double limit = InputFilters::kMaxControlDtSec;
  f.update(sample(fromSec(1.1 + limit - 0.01), 10.0), p);
  EXPECT_NEAR(f.controlDt(), limit - 0.01, 1e-9);  // just under the limit: as is
  f.update(sample(fromSec(30.0), 10.0), p);
  EXPECT_DOUBLE_EQ(f.controlDt(), limit);  // a stall: clipped
}

TEST(InputFiltersPart, PidSignalFollowsItsSource) {
  Params p;
  p.OutputPIDFilterTC = 1000.0;
  InputFilters f;
  f.update(sample(fromSec(1.0), 0.0), p);
  f.update(sample(fromSec(1.1), 50.0), p);
  const double ema = f.pidFiltered().value();
  EXPECT_GT(ema, 0.0);
  EXPECT_LT(ema, 50.0);
  p.OutputPIDSigSrc = 2;  // raw
  f.update(sample(fromSec(1.2), 50.0), p);
  EXPECT_DOUBLE_EQ(f.pidSignal(), 50.0);
  p.OutputPIDSigSrc = 0;  // the EMA
  f.update(sample(fromSec(1.3), 50.0), p);
  EXPECT_DOUBLE_EQ(f.pidSignal(), f.pidFiltered().value());
}

TEST(InputFiltersPart, IbvSlopeBetweenFreshSamplesOnly) {
  Params p;
  p.VoltageFilterTC = 0.0;  // pass the raw voltage
  InputFilters f;
  ControlSensors s = sample(fromSec(1.0), 10.0);
  s.ibvFresh = true;
  s.IBV = 13.0;
  f.update(s, p);
  s.now = fromSec(1.5);
  s.IBV = 13.1;
  s.ibvFresh = false;  // a stale repeat does not count
  f.update(s, p);
  EXPECT_DOUBLE_EQ(f.ibvSlope(), 0.0);
  s.now = fromSec(2.0);
  s.ibvFresh = true;
  f.update(s, p);
  EXPECT_NEAR(f.ibvSlope(), 0.1, 1e-9);  // 0.1 V over 1 s
}

}  // namespace
}  // namespace xr

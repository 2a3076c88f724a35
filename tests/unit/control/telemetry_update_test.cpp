// ControlLaw::updateTelemetry() (Regulator's incremental fill of a persistent
// struct) must always equal a full fillTelemetry(): every field, every tick,
// through TuningMode, CVTuningMode and SystemID runs, their commits and the
// ticks where they stop.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "law_rig.h"

namespace xr::test {
namespace {

std::vector<double> fields(const ControlTelemetry& t) {
  std::vector<double> v;
  visitControlTelemetry(t, [&](const char*, const auto& x) { v.push_back(static_cast<double>(x)); });
  return v;
}

TEST(ControlTelemetryUpdate, IncrementalUpdateEqualsFullFillEveryTick) {
  LawRig rig;
  rig.plant.deadTime = 0.02;
  rig.start();
  ControlTelemetry persistent;
  int tuningTicks = 0;
  int sysIdTicks = 0;
  bool sysIdDone = false;
  for (long i = 0; i < 12000; ++i) {
    if (i == 400) rig.p.TuningMode = 1;
    if (i == 2000) {
      EXPECT_TRUE(rig.law.commitTuning(rig.now, rig.p));
    }
    if (i == 2400) rig.p.TuningMode = 0;
    if (i == 3000) rig.p.CVTuningMode = 1;
    if (i == 4500) {
      EXPECT_TRUE(rig.law.commitCvTuning(rig.now, rig.p));
    }
    if (i == 5000) rig.p.CVTuningMode = 0;
    if (i == 7000) {
      ASSERT_TRUE(rig.law.startSystemId(rig.now, true));
    }
    rig.tick();
    rig.law.updateTelemetry(persistent);
    ControlTelemetry full;
    rig.law.fillTelemetry(full);
    const std::vector<double> a = fields(persistent), b = fields(full);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t k = 0; k < a.size(); ++k)
      ASSERT_EQ(std::memcmp(&a[k], &b[k], sizeof(double)), 0) << "field " << k << " at tick " << i;
    tuningTicks += full.tuningRunning || full.cvTuningRunning;
    sysIdTicks += full.sysIDRunning;
    sysIdDone = sysIdDone || full.sysIDValid;
  }
  // The run really exercised the slow fields.
  EXPECT_GT(tuningTicks, 1000);
  EXPECT_GT(sysIdTicks, 10);
  EXPECT_TRUE(sysIdDone);
}

}  // namespace
}  // namespace xr::test

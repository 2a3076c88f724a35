// Regulator::step with Inputs::telemetryWanted false defers the telemetry
// that is a pure function of the state; completeTelemetry() must then give
// exactly what a step with telemetryWanted true would have returned. Two
// regulators see the same inputs: one wants every tick's telemetry, the
// other only some, and completes the rest at chosen ticks. Every telemetry
// field (the CSV columns and the control/protection/battery blocks) must be
// bit-identical wherever the second one is complete.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <string_view>
#include <type_traits>
#include <vector>

#include "control/telemetry.h"
#include "reg_rig.h"

namespace xr::test {
namespace {

std::vector<std::uint64_t> bitsOf(const Telemetry& t) {
  std::vector<std::uint64_t> v;
  auto put = [&](const auto& x) {
    using T = std::decay_t<decltype(x)>;
    if constexpr (std::is_same_v<T, double>)
      v.push_back(std::bit_cast<std::uint64_t>(x));
    else if constexpr (std::is_enum_v<T>)
      v.push_back(static_cast<std::uint64_t>(x));
    else
      v.push_back(static_cast<std::uint64_t>(x));
  };
  visitTelemetryColumns(t, 0, [&](std::string_view, const ColumnValue& c) {
    if (const double* d = std::get_if<double>(&c))
      put(*d);
    else if (const bool* b = std::get_if<bool>(&c))
      put(*b);
    else
      v.push_back(std::hash<std::string_view>{}(std::get<std::string_view>(c)));
  });
  auto field = [&](const char*, const auto& x) { put(x); };
  visitControlTelemetry(t.control, field);
  visitProtectionTelemetry(t.protection, field);
  visitBatteryTelemetry(t.battery, field);
  return v;
}

// Drives two regulators with the same inputs and operator actions.
struct Pair {
  RegRig always;
  Regulator lazy{always.p};

  void setParams(const Params& p) {
    always.p = p;
    always.reg.setParams(p);
    lazy.setParams(p);
  }
  void command(const Command& c) { EXPECT_EQ(always.reg.command(c), lazy.command(c)); }
  // One tick; returns the lazy regulator's outputs (complete only if wanted).
  const Outputs& tick(bool wanted) {
    always.now += fromSec(0.0025);
    if (always.now - always.tempStamp >= fromSec(1.0)) always.tempStamp = always.now;
    Inputs in = always.inputs();
    const Outputs& a = always.reg.step(in);
    in.telemetryWanted = wanted;
    const Outputs& b = lazy.step(in);
    // The control path never depends on the telemetry.
    EXPECT_EQ(std::bit_cast<std::uint64_t>(a.dutyPct), std::bit_cast<std::uint64_t>(b.dutyPct));
    EXPECT_EQ(a.fieldEnable, b.fieldEnable);
    EXPECT_EQ(a.events.count, b.events.count);
    always.plant.advance(a.dutyPct, a.fieldEnable, 0.0025);
    return b;
  }
};

Command cmd(CommandType t, double value = 0.0) {
  Command c;
  c.type = t;
  c.value = value;
  return c;
}

// `wantEvery`: the lazy regulator wants telemetry every Nth tick (0: never);
// `completeEvery`: it completes the telemetry every Mth tick (0: never).
void runAndCompare(long wantEvery, long completeEvery) {
  Pair pr;
  long compared = 0, deferred = 0;
  for (long i = 1; i <= 24000; ++i) {
    // Operator and parameter changes that move the slow and latched fields.
    Params p = pr.always.p;
    if (i == 1000) p.TuningMode = 1;
    if (i == 3000) p.TuningMode = 0;
    if (i == 4000) p.CVTuningMode = 1;
    if (i == 6000) p.CVTuningMode = 0;
    if (i == 1000 || i == 3000 || i == 4000 || i == 6000) pr.setParams(p);
    if (i == 2000) pr.command(cmd(CommandType::TuningCommit));
    if (i == 5000) pr.command(cmd(CommandType::CvTuningCommit));
    if (i == 7000) pr.command(cmd(CommandType::SystemIdStart));
    if (i == 9000) pr.command(cmd(CommandType::Off));  // disabled ramp: govMode from the sequencer
    if (i == 11000) pr.command(cmd(CommandType::Auto));
    if (i == 12000) pr.command(cmd(CommandType::Manual, 30.0));
    if (i == 13000) pr.command(cmd(CommandType::LimpHome));
    if (i == 14000) pr.command(cmd(CommandType::LimpHomeOff));
    if (i == 14001) pr.command(cmd(CommandType::Auto));
    if (i == 15000) pr.command(cmd(CommandType::SetSoc, 55.0));
    if (i == 16000) pr.command(cmd(CommandType::ResetAltZero));
    if (i == 18000) pr.always.rpm = 300.0;  // below the minimum RPM: a protection ramp
    if (i == 20000) pr.always.rpm = 2000.0;
    if (i == 21000) pr.always.tempF = 260.0;  // thermal derate and temperature warnings
    const bool wanted = wantEvery > 0 && i % wantEvery == 0;
    const Outputs* b = &pr.tick(wanted);
    deferred += !wanted;
    const bool complete = completeEvery > 0 && i % completeEvery == 0;
    if (!wanted && !complete) continue;
    if (complete) b = &pr.lazy.completeTelemetry();
    const std::vector<std::uint64_t> x = bitsOf(pr.always.reg.outputs().telemetry), y = bitsOf(b->telemetry);
    ASSERT_EQ(x.size(), y.size());
    for (std::size_t k = 0; k < x.size(); ++k) ASSERT_EQ(x[k], y[k]) << "field " << k << " at tick " << i;
    ++compared;
  }
  EXPECT_GT(compared, 10);
  if (wantEvery != 1) {
    EXPECT_GT(deferred, 10000);
  }
}

TEST(DeferredTelemetry, EveryTickWantedEqualsTheAlwaysWantedRun) { runAndCompare(1, 0); }
TEST(DeferredTelemetry, ThinnedLikeTheRuntimeEqualsTheAlwaysWantedRun) { runAndCompare(40, 0); }
TEST(DeferredTelemetry, CompletedAfterLongGapsEqualsTheAlwaysWantedRun) { runAndCompare(0, 997); }
TEST(DeferredTelemetry, WantedAndCompletedMixedEqualsTheAlwaysWantedRun) { runAndCompare(400, 37); }

TEST(DeferredTelemetry, CompletingTwiceChangesNothing) {
  Pair pr;
  for (long i = 0; i < 4000; ++i) pr.tick(false);
  const std::vector<std::uint64_t> once = bitsOf(pr.lazy.completeTelemetry().telemetry);
  EXPECT_EQ(bitsOf(pr.lazy.completeTelemetry().telemetry), once);
  EXPECT_EQ(once, bitsOf(pr.always.reg.outputs().telemetry));
}

}  // namespace
}  // namespace xr::test

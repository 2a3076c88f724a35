// updateTelemetry() (Regulator's incremental fill of a persistent struct)
// must always equal a full fillTelemetry(): every field, every tick, through
// SoC bodies, charge-time updates, an auto-zero, a full charge, Victron
// switching and every command / setParams / restoreLedger between ticks.
#include <gtest/gtest.h>

#include <cstring>

#include "battery_fixture.h"

namespace xr::test {
namespace {

// Compares field by field through the exporters' own list.
void expectSame(const BatteryTelemetry& a, const BatteryTelemetry& b, long tick) {
  std::vector<double> va, vb;
  visitBatteryTelemetry(a, [&](const char*, const auto& v) { va.push_back(static_cast<double>(v)); });
  visitBatteryTelemetry(b, [&](const char*, const auto& v) { vb.push_back(static_cast<double>(v)); });
  ASSERT_EQ(va.size(), vb.size());
  for (std::size_t i = 0; i < va.size(); ++i)
    ASSERT_EQ(std::memcmp(&va[i], &vb[i], sizeof(double)), 0) << "field " << i << " at tick " << tick;
}

TEST(BatteryTelemetry, IncrementalUpdateEqualsFullFillEveryTick) {
  Params p;
  p.AutoAltCurrentZero = true;
  p.TempSource = 0;
  p.BatteryCurrentSource = 3;
  p.SOCUpdateInterval = 500;
  p.ChargedDetectionTime = 20;
  p.ChargedVoltage = 13.2;
  BatteryRig r(p);
  BatteryTelemetry persistent;
  int changesSeen = 0;
  double lastSoc = -1.0;
  for (long i = 0; i < 40000; ++i) {
    r.in.rpm = Reading{1500.0, r.now, true};
    r.in.AlternatorTemperatureF = Reading{100.0 + (i > 20000 ? 30.0 : 0.0), r.now, true};
    const double amps = i < 15000 ? 20.0 : (i < 30000 ? 0.5 : -15.0);
    r.ina(13.6, amps);
    r.in.VictronCurrent = Reading{7.0, i % 9000 < 4500 ? r.now : 0, i % 9000 < 4500};
    // Commands land on ticks that run neither the SoC body (every 50 ticks)
    // nor the prediction (every 110), so a missed refresh shows.
    if (i == 5007) r.mon.setSoc(40.0);
    if (i == 26013) r.mon.resetAltZero();  // after the auto-zero (temperature shift at 20000)
    if (i == 12003) r.mon.resetSocGain();
    if (i == 25011) {
      Params q = p;
      q.BatteryCapacity_Ah = 200.0;
      r.mon.setParams(q);
    }
    if (i == 33017) r.mon.restoreLedger(r.mon.ledger());
    r.tick(0.01, 3.0);  // short ticks: most of them run neither the SoC body nor the prediction
    r.mon.updateTelemetry(persistent);
    expectSame(persistent, r.telem(), i);
    if (persistent.SOC_percent != lastSoc) ++changesSeen;
    lastSoc = persistent.SOC_percent;
  }
  // The run really moved the slow fields (else the comparison proves little).
  EXPECT_GT(changesSeen, 20);
}

}  // namespace
}  // namespace xr::test

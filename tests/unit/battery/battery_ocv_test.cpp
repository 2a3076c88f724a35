// The first SoC from the rested voltage (docs/batteries.md "State of charge
// at first start"): a lead-acid bank at rest gets an estimate from the
// Lifeline AGM table; a LiFePO4 or custom bank stays unknown until a full
// charge or a value set; the source survives a restart.
#include "battery/battery_ocv.h"

#include <gtest/gtest.h>

#include <cmath>

#include "battery/battery_monitor.h"
#include "battery/resistance_estimator.h"
#include "battery_fixture.h"

namespace xr {
namespace {

using test::BatteryRig;

Params agm200() {
  Params p;
  p.BatteryCapacity_Ah = 200.0;
  p.BatteryProfile = 1;  // agm
  p.SOCUpdateInterval = 2000;
  p.CurrentThreshold = 1.0;
  return p;
}

TEST(SocAtFirstStart, ALeadAcidBankAtRestIsEstimatedFromItsVoltage) {
  BatteryRig r(agm200());
  ASSERT_EQ(r.mon.socSource(), SocSource::Unknown);
  r.ina(11.96, -2.0);  // 35 % on the rest-voltage tables; a 2 A house load (1 % C)
  r.run(29.0, 0.1);
  EXPECT_EQ(r.mon.socSource(), SocSource::Unknown) << "before 30 s of rest";
  r.run(2.0, 0.1);
  ASSERT_EQ(r.mon.socSource(), SocSource::OcvEstimate);
  // 11.96 V lies between Lifeline's 25 % (11.75 V) and 50 % (12.20 V): 36.7 %.
  EXPECT_NEAR(r.mon.socPercent(), 36.7, 0.5);
  EXPECT_FALSE(r.mon.socKnown());  // an estimate gates nothing
  EXPECT_EQ(r.telem().socSource, SocSource::OcvEstimate);
}

TEST(SocAtFirstStart, A24VoltBankIsReadPer12Volts) {
  Params p = agm200();
  p.BatteryCells = 12;
  BatteryRig r(p);
  r.ina(24.40, 0.0);  // 12.20 V per 12 V: 50 %
  r.run(31.0, 0.1);
  ASSERT_EQ(r.mon.socSource(), SocSource::OcvEstimate);
  EXPECT_NEAR(r.mon.socPercent(), 50.0, 0.5);
}

TEST(SocAtFirstStart, NoEstimateUnderLoadOrWhileCharging) {
  BatteryRig loaded(agm200());
  loaded.ina(11.90, -5.0);  // 2.5 % C: the voltage sags under it
  loaded.run(60.0, 0.1);
  EXPECT_EQ(loaded.mon.socSource(), SocSource::Unknown);
  BatteryRig charging(agm200());
  charging.ina(13.2, 0.5);
  charging.run(60.0, 0.1, 30.0);  // the alternator gives 30 A to the house loads
  EXPECT_EQ(charging.mon.socSource(), SocSource::Unknown);
}

TEST(SocAtFirstStart, LiFePO4AndCustomStayUnknownUntilAFullCharge) {
  for (int profile : {0, 4}) {
    Params p = agm200();
    p.BatteryProfile = profile;
    BatteryRig r(p);
    r.ina(13.1, 0.0);
    r.run(120.0, 0.1);
    EXPECT_EQ(r.mon.socSource(), SocSource::Unknown) << "profile " << profile;
    r.mon.setSoc(55.0);
    EXPECT_EQ(r.mon.socSource(), SocSource::Counted);
  }
}

TEST(SocAtFirstStart, TheSourceSurvivesARestartAndOldLedgersCountAsKnown) {
  BatteryRig r(agm200());
  r.ina(12.20, 0.0);
  r.run(31.0, 0.1);
  ASSERT_EQ(r.mon.socSource(), SocSource::OcvEstimate);
  BatteryRig again(agm200());
  again.mon.restoreLedger(r.mon.ledger());
  EXPECT_EQ(again.mon.socSource(), SocSource::OcvEstimate);
  EXPECT_NEAR(again.mon.socPercent(), 50.0, 0.5);
  // A database from before SocSource has no row for it: BatteryLedger's default.
  BatteryLedger old = r.mon.ledger();
  old.SocSource = BatteryLedger{}.SocSource;
  BatteryRig upgraded(agm200());
  upgraded.mon.restoreLedger(old);
  EXPECT_EQ(upgraded.mon.socSource(), SocSource::Counted);
  // A damaged value is unknown, not trusted.
  old.SocSource = 7.5;
  BatteryRig damaged(agm200());
  damaged.mon.restoreLedger(old);
  EXPECT_EQ(damaged.mon.socSource(), SocSource::Unknown);
}

// OcvReanchor on its own: the first-start estimate at 30 s of rest and not
// before, a load above the rest limit restarts it; the rested point at 4 h.
RestInput restAt(double volts, double amps, double dt = 1.0) {
  RestInput in;
  in.dt_s = dt;
  in.volts = volts;
  in.amps = amps;
  in.altAmps = 0.0;
  in.tempC = kNoValue;
  return in;
}

TEST(OcvReanchor, FirstStartEstimateAtThirtySecondsOfRestNotBefore) {
  const Params p = agm200();
  OcvReanchor o;
  for (int i = 0; i < 29; ++i) EXPECT_TRUE(std::isnan(o.firstStartEstimate(restAt(12.20, 0.0), true, p)));
  EXPECT_NEAR(o.firstStartEstimate(restAt(12.20, 0.0), true, p), 50.0, 1e-9);
  // Not while the SoC is known, nor under a load above 2 % of C.
  OcvReanchor known, loaded;
  for (int i = 0; i < 40; ++i) {
    EXPECT_TRUE(std::isnan(known.firstStartEstimate(restAt(12.20, 0.0), false, p)));
    EXPECT_TRUE(std::isnan(loaded.firstStartEstimate(restAt(12.20, i == 20 ? -4.01 : 0.0), true, p))) << i;
  }
}

TEST(OcvReanchor, ARestedPointAfterFourHoursIsTakenOnce) {
  const Params p = agm200();
  OcvReanchor o;
  ResistanceEstimator r;  // no resistance known: the terminal voltage is the OCV
  for (int i = 0; i < 4 * 3600 - 1; ++i) o.trackRestedPoint(restAt(12.55, -1.0), p, r);
  EXPECT_TRUE(std::isnan(o.takeRestedPoint())) << "one second short of 4 h";
  o.trackRestedPoint(restAt(12.55, -1.0), p, r);
  EXPECT_NEAR(o.takeRestedPoint(), 75.0, 1e-9);
  EXPECT_TRUE(std::isnan(o.takeRestedPoint())) << "taking it clears it";
  for (int i = 0; i < 3600; ++i) o.trackRestedPoint(restAt(12.55, -1.0), p, r);
  EXPECT_TRUE(std::isnan(o.takeRestedPoint())) << "one point per rest";
}

TEST(OcvReanchor, NoRestedPointForLiFePO4) {
  Params p = agm200();
  p.BatteryProfile = 0;
  OcvReanchor o;
  ResistanceEstimator r;
  for (int i = 0; i < 4 * 3600 + 10; ++i) o.trackRestedPoint(restAt(13.2, 0.0), p, r);
  EXPECT_TRUE(std::isnan(o.takeRestedPoint()));
}

}  // namespace
}  // namespace xr

// EnergyCounter on its own (docs/batteries.md "Energy"): the split into
// charge and discharge, the alternator's and solar's share, the lifetime
// total's whole Wh at 1 Wh and its fraction below, fuel in 0.01 L steps,
// restore.
#include "battery/energy_counter.h"

#include <gtest/gtest.h>

#include <cmath>

namespace xr {
namespace {

EnergySample sample(double volts, double amps, double dt = 3600.0) {
  EnergySample s;
  s.dt_s = dt;
  s.volts = volts;
  s.amps = amps;
  s.voltsOk = s.ampsOk = true;
  s.solarW = std::nan("");
  return s;
}

TEST(EnergyCounter, ChargeAndDischargeAreCountedApart) {
  EnergyCounter e;
  e.integrate(sample(12.5, 2.0));   // 25 Wh in
  e.integrate(sample(12.0, -1.0));  // 12 Wh out
  e.commit();
  EXPECT_DOUBLE_EQ(e.charged().session_Wh, 25.0);
  EXPECT_DOUBLE_EQ(e.discharged().session_Wh, 12.0);
  EXPECT_DOUBLE_EQ(e.charged().lifetime(), 25.0);
}

TEST(EnergyCounter, ALifetimeTotalKeepsItsFractionBelowOneWattHour) {
  EnergyCounter e;
  e.integrate(sample(12.0, 0.08));  // 0.96 Wh: all fraction
  e.commit();
  EXPECT_DOUBLE_EQ(e.charged().lifetimeWhole_Wh, 0.0);
  EXPECT_NEAR(e.charged().lifetimeFraction_Wh, 0.96, 1e-12);
  e.integrate(sample(12.0, 0.01, 1800.0));  // 0.06 Wh: 1.02 Wh in all
  e.commit();
  EXPECT_DOUBLE_EQ(e.charged().lifetimeWhole_Wh, 1.0);
  EXPECT_NEAR(e.charged().lifetimeFraction_Wh, 0.02, 1e-12);
}

TEST(EnergyCounter, AlternatorTimeEnergyAndFuel) {
  EnergyCounter e;
  EnergySample s = sample(14.0, 0.0);
  s.alternatorOn = true;
  s.altAmps = 100.0;  // 1400 Wh in an hour
  e.integrate(s);
  e.commit();
  EXPECT_DOUBLE_EQ(e.alternator().session_Wh, 1400.0);
  EXPECT_DOUBLE_EQ(e.alternatorOnTime_s(), 3600.0);
  // 1400 Wh / (0.30 x 0.50) = 33.6 MJ of diesel, 36 kJ/mL: 0.933 L, in 0.01 L steps.
  EXPECT_NEAR(e.fuelUsed_L(), 0.93, 1e-9);
  EXPECT_DOUBLE_EQ(e.fuelUsedAllTime_L(), e.fuelUsed_L());
  EnergySample off = sample(14.0, 0.0);
  off.altAmps = 100.0;  // not above CurrentThreshold (alternatorOn false): nothing counts
  e.integrate(off);
  e.commit();
  EXPECT_DOUBLE_EQ(e.alternatorOnTime_s(), 3600.0);
}

TEST(EnergyCounter, SolarCountsOnlyAFreshPositivePower) {
  EnergyCounter e;
  EnergySample s = sample(13.0, 0.0);
  s.solarW = 80.0;
  e.integrate(s);
  s.solarW = -5.0;
  e.integrate(s);
  e.commit();
  EXPECT_DOUBLE_EQ(e.solar().session_Wh, 80.0);
}

TEST(EnergyCounter, RestoreSplitsTotalsAndRefusesDamage) {
  BatteryLedger l;
  l.ChargedEnergy_AllTime_Wh = 1234.5;
  l.DischargedEnergy_AllTime_Wh = -5.0;
  l.AlternatorFuelUsed_AllTime_L = std::nan("");
  EnergyCounter e;
  e.restore(l);
  EXPECT_DOUBLE_EQ(e.charged().lifetimeWhole_Wh, 1234.0);
  EXPECT_DOUBLE_EQ(e.charged().lifetimeFraction_Wh, 0.5);
  EXPECT_DOUBLE_EQ(e.discharged().lifetime(), 0.0);
  EXPECT_DOUBLE_EQ(e.fuelUsedAllTime_L(), 0.0);
  BatteryLedger out;
  e.toLedger(out);
  EXPECT_DOUBLE_EQ(out.ChargedEnergy_AllTime_Wh, 1234.5);
}

}  // namespace
}  // namespace xr

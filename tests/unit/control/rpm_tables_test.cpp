#include "control/rpm_tables.h"

#include <gtest/gtest.h>

#include <cmath>

namespace xr {
namespace {

Params rampTable() {
  Params p;
  p.rpmCapCurrentTable = {10, 20, 30, 40, 50, 60, 70, 80, 90, 100};
  return p;
}

TEST(RpmTables, Interpolation_AtOrBelowFirstBreakpointUsesFirstEntry) {
  const Params p = rampTable();
  EXPECT_DOUBLE_EQ(interpolateRpmTable(p.rpmTableRPMPoints, p.rpmCapCurrentTable, 100.0), 10.0);
  EXPECT_DOUBLE_EQ(interpolateRpmTable(p.rpmTableRPMPoints, p.rpmCapCurrentTable, 0.0), 10.0);
  EXPECT_DOUBLE_EQ(interpolateRpmTable(p.rpmTableRPMPoints, p.rpmCapCurrentTable, -500.0), 10.0);
}

TEST(RpmTables, Interpolation_LinearBetweenBreakpointsAndExactAtThem) {
  const Params p = rampTable();
  EXPECT_DOUBLE_EQ(interpolateRpmTable(p.rpmTableRPMPoints, p.rpmCapCurrentTable, 600.0), 20.0);
  EXPECT_DOUBLE_EQ(interpolateRpmTable(p.rpmTableRPMPoints, p.rpmCapCurrentTable, 350.0), 15.0);
  EXPECT_DOUBLE_EQ(interpolateRpmTable(p.rpmTableRPMPoints, p.rpmCapCurrentTable, 4350.0), 95.0);
  EXPECT_NEAR(interpolateRpmTable(p.rpmTableRPMPoints, p.rpmCapCurrentTable, 1100.0 + 125.0), 32.5, 1e-12);
}

TEST(RpmTables, Interpolation_NoExtrapolationAboveLastBreakpoint) {
  const Params p = rampTable();
  EXPECT_DOUBLE_EQ(interpolateRpmTable(p.rpmTableRPMPoints, p.rpmCapCurrentTable, 4600.0), 100.0);
  EXPECT_DOUBLE_EQ(interpolateRpmTable(p.rpmTableRPMPoints, p.rpmCapCurrentTable, 9000.0), 100.0);
}

TEST(RpmTables, Interpolation_NanRpmGivesFirstEntrySafeZeroByDefault) {
  const Params p;  // default cap table starts at 0
  EXPECT_DOUBLE_EQ(getCapCurrentForRPM(p, std::nan(""), 13.0), 0.0);
}

TEST(RpmTables, DefaultCapIsZeroWhenEngineStopped) {
  const Params p;
  EXPECT_DOUBLE_EQ(getCapCurrentForRPM(p, 50.0, 13.0), 0.0);
  EXPECT_DOUBLE_EQ(getCapCurrentForRPM(p, 2000.0, 13.0), 50.0);
}

TEST(RpmTables, CapInKwModeConvertsThroughLiveIBV) {
  Params p;
  p.capLimitMode = 1;
  p.rpmCapPowerTable = {0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0};
  EXPECT_NEAR(getCapCurrentForRPM(p, 2000.0, 12.5), 80.0, 1e-9);  // 1 kW / 12.5 V
  EXPECT_NEAR(getCapCurrentForRPM(p, 2000.0, 14.0), 1000.0 / 14.0, 1e-9);
  // Amps table ignored in kW mode.
  p.rpmCapCurrentTable = {0, 5, 5, 5, 5, 5, 5, 5, 5, 5};
  EXPECT_NEAR(getCapCurrentForRPM(p, 2000.0, 12.5), 80.0, 1e-9);
}

TEST(RpmTables, CapInKwModeWithoutUsableVoltageIsZero) {
  Params p;
  p.capLimitMode = 1;
  p.rpmCapPowerTable = {0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0};
  EXPECT_DOUBLE_EQ(getCapCurrentForRPM(p, 2000.0, std::nan("")), 0.0);
  EXPECT_DOUBLE_EQ(getCapCurrentForRPM(p, 2000.0, 0.0), 0.0);
}

TEST(RpmTables, LowChargeRateLoadsLowTablesNotAHalving) {
  Params p;
  p.HiLow = 0;
  p.rpmCapCurrentTableLo = {0, 7, 7, 7, 7, 7, 7, 7, 7, 7};  // deliberately not 1/2 or 1/4 of Normal
  EXPECT_DOUBLE_EQ(getCapCurrentForRPM(p, 2000.0, 13.0), 7.0);
  p.HiLow = 1;
  EXPECT_DOUBLE_EQ(getCapCurrentForRPM(p, 2000.0, 13.0), 50.0);
  p.HiLow = 0;
  p.capLimitMode = 1;
  p.rpmCapPowerTableLo = {0, 0.26, 0.26, 0.26, 0.26, 0.26, 0.26, 0.26, 0.26, 0.26};
  EXPECT_NEAR(getCapCurrentForRPM(p, 2000.0, 13.0), 20.0, 1e-9);
}

TEST(RpmTables, MinDutyInterpolatesAndFollowsHiLow) {
  Params p;
  EXPECT_DOUBLE_EQ(getMinDutyForRPM(p, 100.0), 5.0);
  EXPECT_DOUBLE_EQ(getMinDutyForRPM(p, 1350.0), 4.0);
  EXPECT_DOUBLE_EQ(getMinDutyForRPM(p, 1850.0), 3.5);
  EXPECT_DOUBLE_EQ(getMinDutyForRPM(p, 6000.0), 1.0);
  p.HiLow = 0;
  p.rpmMinDutyTableLo = {9, 9, 9, 9, 9, 9, 9, 9, 9, 9};
  EXPECT_DOUBLE_EQ(getMinDutyForRPM(p, 1850.0), 9.0);
}

}  // namespace
}  // namespace xr

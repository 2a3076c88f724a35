#include <gtest/gtest.h>

#include "params/derived.h"

namespace xr {
namespace {

Params withBulk(double v) {
  Params p;
  p.BulkVoltage = v;
  return p;
}

TEST(Derived, SystemClassFromBulkVoltage) {
  EXPECT_EQ(systemClass(withBulk(14.5)), SystemClass::V12);
  EXPECT_EQ(systemClass(withBulk(17.99)), SystemClass::V12);
  EXPECT_EQ(systemClass(withBulk(18.0)), SystemClass::V24);
  EXPECT_EQ(systemClass(withBulk(29.0)), SystemClass::V24);
  EXPECT_EQ(systemClass(withBulk(57.6)), SystemClass::V48);
}

TEST(Derived, PlausibleRangesMatchTheSeedTable) {
  auto r12 = plausibleVoltageRange(withBulk(14.5));
  EXPECT_DOUBLE_EQ(r12.min, 4.5);
  EXPECT_DOUBLE_EQ(r12.max, 15.5);
  auto r24 = plausibleVoltageRange(withBulk(28.8));
  EXPECT_DOUBLE_EQ(r24.min, 9.0);
  EXPECT_DOUBLE_EQ(r24.max, 30.5);
  auto r48 = plausibleVoltageRange(withBulk(57.6));
  EXPECT_DOUBLE_EQ(r48.min, 18.0);
  EXPECT_DOUBLE_EQ(r48.max, 60.5);
}

TEST(Derived, CriticalDisagreementScalesWithClass) {
  EXPECT_DOUBLE_EQ(criticalDisagreementThreshold(withBulk(14.5)), 1.0);
  EXPECT_DOUBLE_EQ(criticalDisagreementThreshold(withBulk(28.8)), 2.0);
  EXPECT_DOUBLE_EQ(criticalDisagreementThreshold(withBulk(57.6)), 4.0);
}

TEST(Derived, HardShutdownFirstBootDefaultThenAbsolute) {
  Params p = withBulk(14.5);
  EXPECT_DOUBLE_EQ(alternatorHardShutdownV(p), 14.8);
  p.BulkVoltage = 28.8;
  EXPECT_DOUBLE_EQ(alternatorHardShutdownV(p), 29.1);
  p.AlternatorHardShutdownV = 15.0;  // once saved, absolute
  p.BulkVoltage = 14.0;
  EXPECT_DOUBLE_EQ(alternatorHardShutdownV(p), 15.0);
}

TEST(Derived, HardwareLimitAndHardOc) {
  Params p = withBulk(14.5);
  EXPECT_DOUBLE_EQ(voltageHardwareLimit(p), 14.8);
  p.MaxTableValue = 120;
  EXPECT_DOUBLE_EQ(hardOCTripAmps(p), 130);
}

}  // namespace
}  // namespace xr

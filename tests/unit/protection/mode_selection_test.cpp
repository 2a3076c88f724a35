// selectFieldControlMode / selectFieldEventReason: the pure priority function.
#include "protection/mode_selection.h"

#include <gtest/gtest.h>

namespace xr {
namespace {

using M = FieldControlMode;

TickSnapshot healthy() { return TickSnapshot{}; }

TEST(ModeSelection, HealthyAutoIsNormalAutoPid) {
  EXPECT_EQ(selectFieldControlMode(healthy()), M::MODE_NORMAL_AUTO_PID);
  EXPECT_EQ(selectFieldEventReason(healthy()), Reason::NONE);
}

TEST(ModeSelection, InaLatchBeatsEverythingIncludingLimpHome) {
  TickSnapshot s = healthy();
  s.prot.inaOvervoltageLatched = true;
  s.prot.hardOvercurrent = true;
  s.prot.tempCritical = true;
  s.limpHome = true;
  EXPECT_EQ(selectFieldControlMode(s), M::MODE_CRITICAL_RAMP);
  EXPECT_EQ(selectFieldEventReason(s), Reason::REASON_INA_OVERVOLTAGE);
}

TEST(ModeSelection, TwoSimultaneousFaultsHigherPriorityWins) {
  struct Case {
    void (*set)(ProtectionFlags&);
    Reason expect;
  };
  const Case cases[] = {
      {[](ProtectionFlags& f) { f.hardOvercurrent = f.tempCritical = true; },
       Reason::REASON_HARD_OVERCURRENT},
      {[](ProtectionFlags& f) { f.tempCritical = f.voltageDisagreeCritical = true; },
       Reason::REASON_TEMP_CRITICAL},
      {[](ProtectionFlags& f) { f.rpmBelowMin = f.tempStale = true; }, Reason::REASON_RPM_LOW},
      {[](ProtectionFlags& f) { f.tempCritical = f.rpmBelowMin = true; }, Reason::REASON_TEMP_CRITICAL},
      {[](ProtectionFlags& f) { f.voltageImplausible = f.altHardShutdown = true; },
       Reason::REASON_ALT_HARD_SHUTDOWN},
      {[](ProtectionFlags& f) { f.hardOvercurrent = f.altHardShutdown = true; },
       Reason::REASON_ALT_HARD_SHUTDOWN},
      {[](ProtectionFlags& f) { f.inaOvervoltageLatched = f.altHardShutdown = true; },
       Reason::REASON_INA_OVERVOLTAGE},
      {[](ProtectionFlags& f) { f.currentStale = f.tempWarning = true; }, Reason::REASON_CURRENT_STALE},
      {[](ProtectionFlags& f) { f.altHardShutdown = f.tempWarning = true; },
       Reason::REASON_ALT_HARD_SHUTDOWN},
      {[](ProtectionFlags& f) { f.tempSustained = f.tempWarning = true; }, Reason::REASON_TEMP_SUSTAINED},
      {[](ProtectionFlags& f) { f.lockoutActive = f.tempWarning = true; }, Reason::REASON_LOCKOUT},
      {[](ProtectionFlags& f) { f.lockoutActive = f.hardOvercurrent = true; },
       Reason::REASON_HARD_OVERCURRENT},
      {[](ProtectionFlags& f) { f.tempSoakHold = f.rpmBelowMin = true; }, Reason::REASON_RPM_LOW},
      {[](ProtectionFlags& f) { f.tempSoakHold = f.tempCritical = true; }, Reason::REASON_TEMP_CRITICAL},
      {[](ProtectionFlags& f) { f.tempSoakHold = f.lockoutActive = true; }, Reason::REASON_LOCKOUT},
      {[](ProtectionFlags& f) { f.tempSoakHold = true; }, Reason::REASON_TEMP_SOAK},
      // The bank size check names the cause before its symptoms.
      {[](ProtectionFlags& f) { f.bankMismatch = f.inaOvervoltageLatched = f.altHardShutdown = true; },
       Reason::REASON_BANK_MISMATCH},
      {[](ProtectionFlags& f) { f.bankMismatch = f.lockoutActive = f.voltageImplausible = true; },
       Reason::REASON_BANK_MISMATCH},
  };
  for (const Case& c : cases) {
    TickSnapshot s = healthy();
    c.set(s.prot);
    EXPECT_EQ(selectFieldEventReason(s), c.expect) << toString(c.expect);
  }
}

TEST(ModeSelection, ManualBypassesAutoOnlyProtectionsButNotPriorityOne) {
  TickSnapshot s = healthy();
  s.manualMode = true;
  s.prot.voltageDisagreeCritical = s.prot.tempStale = s.prot.lockoutActive = s.prot.inaAbsent = true;
  EXPECT_EQ(selectFieldControlMode(s), M::MODE_NORMAL_MANUAL);
  s.prot.tempCritical = true;
  EXPECT_EQ(selectFieldEventReason(s), Reason::REASON_TEMP_CRITICAL);
  s.prot.altHardShutdown = true;  // a deviation: the hard over-voltage cut acts in MANUAL too
  EXPECT_EQ(selectFieldEventReason(s), Reason::REASON_ALT_HARD_SHUTDOWN);
  EXPECT_EQ(selectFieldControlMode(s), M::MODE_CRITICAL_RAMP);
}

// A deviation: the alternator hard shutdown cuts in every mode, Limp Home included.
TEST(ModeSelection, AltHardShutdownCutsInLimpHome) {
  TickSnapshot s = healthy();
  s.limpHome = true;
  EXPECT_EQ(selectFieldControlMode(s), M::MODE_LIMP_HOME);
  s.prot.altHardShutdown = true;
  EXPECT_EQ(selectFieldEventReason(s), Reason::REASON_ALT_HARD_SHUTDOWN);
  EXPECT_TRUE(isImmediateCutReason(selectFieldEventReason(s)));
}

// Added here: INADisconnected leaves AUTO without voltage feedback, so AUTO does
// not run (a clean disabled ramp, no alarm); MANUAL still does.
TEST(ModeSelection, NoInaMeansNoAuto) {
  TickSnapshot s = healthy();
  s.prot.inaAbsent = true;
  EXPECT_EQ(selectFieldControlMode(s), M::MODE_DISABLED_RAMP);
  EXPECT_EQ(selectFieldEventReason(s), Reason::REASON_VOLTAGE_IMPLAUSIBLE);
  s.manualMode = true;
  EXPECT_EQ(selectFieldControlMode(s), M::MODE_NORMAL_MANUAL);
}

TEST(ModeSelection, ChargingDisabledGivesDisabledRampWithItsReason) {
  struct Case {
    void (*set)(TickSnapshot&);
    Reason expect;
  };
  const Case cases[] = {
      {[](TickSnapshot& s) { s.ignitionOn = false; }, Reason::REASON_IGNITION_OFF},
      {[](TickSnapshot& s) { s.OnOff = false; }, Reason::REASON_ONOFF_DISABLED},
      {[](TickSnapshot& s) { s.bmsChargeEnabled = false; }, Reason::REASON_BMS_DISABLED},
      {[](TickSnapshot& s) { s.weatherModeActive = true; }, Reason::REASON_WEATHER_MODE},
      {[](TickSnapshot& s) { s.idleStage = true; }, Reason::REASON_IDLE_STAGE},
      {[](TickSnapshot& s) { s.sysOff = true; }, Reason::REASON_SYS_OFF},
  };
  for (const Case& c : cases) {
    TickSnapshot s = healthy();
    c.set(s);
    EXPECT_EQ(selectFieldControlMode(s), M::MODE_DISABLED_RAMP);
    EXPECT_EQ(selectFieldEventReason(s), c.expect);
  }
}

TEST(ModeSelection, FaultsOutrankChargingDisabled) {
  TickSnapshot s = healthy();
  s.OnOff = false;
  s.prot.tempWarning = true;
  EXPECT_EQ(selectFieldControlMode(s), M::MODE_WARNING_RAMP_AND_LOCKOUT);
}

TEST(ModeSelection, LimpHomeObeysOnlyTheExplicitDoNotChargeOrders) {
  TickSnapshot s = healthy();
  s.limpHome = true;
  s.prot.hardOvercurrent = s.prot.tempStale = s.prot.rpmBelowMin = true;
  s.weatherModeActive = true;
  EXPECT_EQ(selectFieldControlMode(s), M::MODE_LIMP_HOME);
  s.bmsChargeEnabled = false;
  EXPECT_EQ(selectFieldControlMode(s), M::MODE_DISABLED_RAMP);
  EXPECT_EQ(selectFieldEventReason(s), Reason::REASON_BMS_DISABLED);
}

TEST(ModeSelection, LatchedRampKeepsItsModeAfterTheTriggerClears) {
  TickSnapshot s = healthy();
  s.prot.rampLatched = true;
  s.prot.rampLatchedMode = M::MODE_WARNING_RAMP_AND_LOCKOUT;
  s.prot.rampLatchedReason = Reason::REASON_TEMP_WARNING;
  EXPECT_EQ(selectFieldControlMode(s), M::MODE_WARNING_RAMP_AND_LOCKOUT);
  EXPECT_EQ(selectFieldEventReason(s), Reason::REASON_TEMP_WARNING);
  s.prot.voltageImplausible = true;  // a critical fault escalates
  EXPECT_EQ(selectFieldControlMode(s), M::MODE_CRITICAL_RAMP);
}

TEST(ModeSelection, AutoZeroUsesLockoutRamp) {
  TickSnapshot s = healthy();
  s.autoZeroActive = true;
  EXPECT_EQ(selectFieldControlMode(s), M::MODE_LOCKOUT_RAMP);
  EXPECT_EQ(selectFieldEventReason(s), Reason::REASON_AUTO_ZERO);
}

TEST(ModeSelection, ImmediateCutReasons) {
  EXPECT_TRUE(isImmediateCutReason(Reason::REASON_INA_OVERVOLTAGE));
  EXPECT_TRUE(isImmediateCutReason(Reason::REASON_HARD_OVERCURRENT));
  EXPECT_TRUE(isImmediateCutReason(Reason::REASON_TEMP_CRITICAL));
  EXPECT_TRUE(isImmediateCutReason(Reason::REASON_RPM_LOW));
  EXPECT_TRUE(isImmediateCutReason(Reason::REASON_ALT_HARD_SHUTDOWN));  // a deviation
  EXPECT_FALSE(isImmediateCutReason(Reason::REASON_TEMP_STALE));
}

}  // namespace
}  // namespace xr

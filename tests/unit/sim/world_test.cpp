// SimWorld: wiring of the plant to the chips, faults, ALERT cutting the field.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "drivers/frontend/analog_frontend.h"
#include "drivers/sim/ina228_model.h"
#include "drivers/sim/sim_clock.h"
#include "drivers/sim/sim_onewire.h"
#include "drivers/sim/sim_world.h"

namespace xr::sim {
namespace {

WorldConfig quiet() {
  WorldConfig c;
  c.noise = NoiseConfig{0, 0, 0, 0, 0, 0};
  return c;
}

std::uint64_t readReg(SimWorld& w, std::uint16_t addr, std::uint8_t reg, int n, int* rc = nullptr) {
  std::uint8_t p = reg, buf[8] = {};
  I2cMsg m[2] = {{addr, false, &p, 1}, {addr, true, buf, std::size_t(n)}};
  const int r = w.i2c().transfer(m);
  if (rc) *rc = r;
  std::uint64_t v = 0;
  for (int i = 0; i < n; ++i) v = (v << 8) | buf[i];
  return v;
}
int writeReg(SimWorld& w, std::uint16_t addr, std::uint8_t reg, std::uint16_t v) {
  std::uint8_t b[3] = {reg, std::uint8_t(v >> 8), std::uint8_t(v)};
  I2cMsg m{addr, false, b, 3};
  return w.i2c().transfer({&m, 1});
}

TEST(SimWorld, InaSeesBatteryVoltageOnVbus) {
  HardwareSettings hw;
  SimWorld w(quiet(), hw);
  w.advanceTo(fromMs(10));
  const double vbus = double(readReg(w, hw.ina228_address, ina228::VBUS, 3) >> 4) * 195.3125e-6;
  EXPECT_NEAR(vbus, w.truth().plant.battery_v, 0.001);
}

TEST(SimWorld, FieldFollowsPwmAndEnable) {
  HardwareSettings hw;
  SimWorld w(quiet(), hw);
  w.simPwm().setEnabled(true);
  w.simPwm().setDutyPercent(50);
  w.advanceTo(fromSec(1));
  EXPECT_EQ(w.truth().plant.field, 0.0);  // enable still low
  w.fieldEnable().set(true);
  w.advanceTo(fromSec(2));
  // The field is R-L fed from the bus: half duty gives half the bus over the
  // field resistance at the winding temperature (settled after 1 s, ~10 L/R).
  const LundellParams& m = w.plant().alternator().machine();
  EXPECT_NEAR(w.truth().plant.field_a,
              0.5 * w.truth().plant.battery_v / (m.field_r_ohm * copperFactor(w.truth().plant.alt_stator_c)),
              0.02);
  EXPECT_TRUE(w.truth().field_on);
  EXPECT_GT(w.truth().plant.alt_a, 10.0);
  ASSERT_GE(w.simFieldEnable().log().size(), 1u);
  EXPECT_EQ(w.simFieldEnable().log().back().t, fromSec(1));
}

TEST(SimWorld, InaAlertOnBovlCutsTheFieldInHardware) {
  HardwareSettings hw;
  WorldConfig c = quiet();
  c.plant.battery.soc_pct = 98.0;  // near the knee: voltage rises fast under charge
  SimWorld w(c, hw);
  writeReg(w, hw.ina228_address, ina228::ADC_CONFIG, (0x9 << 12) | (2 << 9));  // bus only, 150 us
  writeReg(w, hw.ina228_address, ina228::BOVL, std::uint16_t(13.75 / 3.125e-3));
  w.simPwm().setEnabled(true);
  w.simPwm().setDutyPercent(100);
  w.fieldEnable().set(true);
  double peak = 0;
  for (int i = 1; i <= 4000; ++i) {
    w.advanceTo(fromMs(5 * i));
    peak = std::max(peak, w.truth().plant.battery_v);
  }
  // No software acted: the ALERT pin kept the bus near BOVL.
  EXPECT_LT(peak, 13.75 + 0.1);
  EXPECT_GT(peak, 13.7);
  EXPECT_GT(w.ina().conversions(), 0u);
  EXPECT_TRUE(w.simFieldEnable().level());
}

TEST(SimWorld, NackFaultsFailTransfers) {
  HardwareSettings hw;
  SimWorld w(quiet(), hw);
  int rc = 0;
  w.setFault(Fault::ina228_nack, true);
  readReg(w, hw.ina228_address, ina228::MANUFACTURER_ID, 2, &rc);
  EXPECT_EQ(rc, EREMOTEIO);
  readReg(w, hw.ads1115_address, 1, 2, &rc);
  EXPECT_EQ(rc, 0);
  w.setFault(Fault::ina228_nack, false);
  w.setFault(Fault::ads1115_nack, true);
  readReg(w, hw.ina228_address, ina228::MANUFACTURER_ID, 2, &rc);
  EXPECT_EQ(rc, 0);
  readReg(w, hw.ads1115_address, 1, 2, &rc);
  EXPECT_EQ(rc, EREMOTEIO);
}

TEST(SimWorld, AnalogFaultsShiftTheAdsInputs) {
  HardwareSettings hw;
  SimWorld w(quiet(), hw);
  auto ch0 = [&] {
    // single-shot AIN0-GND at ±2.048 V, 860 SPS
    writeReg(w, hw.ads1115_address, 1, std::uint16_t(0x8000 | (4 << 12) | (2 << 9) | 0x100 | (7 << 5) | 3));
    w.advanceTo(w.now() + fromMs(2));
    const auto code = std::int16_t(readReg(w, hw.ads1115_address, 0, 2));
    return frontend::batteryVoltsFromAdc(hw.frontend, code * 2.048 / 32768.0);
  };
  const double v = ch0();
  EXPECT_NEAR(v, w.truth().plant.battery_v, 0.01);
  w.setFault(Fault::battery_v_offset, true, 1.5);
  EXPECT_NEAR(ch0(), v + 1.5, 0.02);
  w.setFault(Fault::battery_v_offset, false);
  w.setFault(Fault::battery_v_zero, true);
  EXPECT_NEAR(ch0(), 0.0, 1e-9);
}

TEST(SimWorld, RpmSignalLossDecaysWithTwoSecondCoupling) {
  HardwareSettings hw;
  SimWorld w(quiet(), hw);
  auto ch2 = [&] {
    writeReg(w, hw.ads1115_address, 1, std::uint16_t(0x8000 | (6 << 12) | (1 << 9) | 0x100 | (7 << 5) | 3));
    w.advanceTo(w.now() + fromMs(2));
    const auto code = std::int16_t(readReg(w, hw.ads1115_address, 0, 2));
    return frontend::rpmFromAdc(hw.frontend, code * 4.096 / 32768.0);
  };
  const double r0 = ch2();
  EXPECT_NEAR(r0, 1800.0, 2.0);
  w.setFault(Fault::rpm_signal_loss, true);
  w.advanceTo(w.now() + fromSec(2.0));
  EXPECT_NEAR(ch2(), r0 * std::exp(-1.0), 30.0);
  w.advanceTo(w.now() + fromSec(20.0));
  EXPECT_EQ(ch2(), 0.0);
}

TEST(SimWorld, FieldOpenFaultKillsOutput) {
  HardwareSettings hw;
  SimWorld w(quiet(), hw);
  w.simPwm().setEnabled(true);
  w.simPwm().setDutyPercent(80);
  w.fieldEnable().set(true);
  w.setFault(Fault::field_open, true);
  w.advanceTo(fromSec(2));
  EXPECT_EQ(w.truth().plant.alt_a, 0.0);
  EXPECT_FALSE(w.truth().field_on);
}

TEST(SimWorld, SameSeedSameNoise) {
  HardwareSettings hw;
  WorldConfig c;
  c.seed = 9;
  SimWorld a(c, hw), b(c, hw);
  for (int i = 1; i < 50; ++i) {
    a.advanceTo(fromMs(3 * i));
    b.advanceTo(fromMs(3 * i));
    EXPECT_EQ(readReg(a, hw.ina228_address, ina228::VSHUNT, 3),
              readReg(b, hw.ina228_address, ina228::VSHUNT, 3));
  }
}

// Ready-edge pacing advances the world to ADS1115 conversion-ready edges
// between control ticks: those advances move the chips, not the plant, so a
// run with them sees exactly the plant of a run without them at every grid
// point (no software acts in between here).
TEST(SimWorld, AdvancesBetweenGridPointsDoNotStepThePlant) {
  HardwareSettings hw;
  WorldConfig c;  // with noise: the extra conversions draw extra noise, the plant must not care
  SimWorld grid(c, hw), edges(c, hw);
  for (SimWorld* w : {&grid, &edges}) {
    w->simPwm().setDutyPercent(70);
    w->fieldEnable().set(true);
  }
  // Conversion-ready mode (Hi_thresh MSB 1, Lo_thresh MSB 0), continuous AIN1, 860 SPS.
  ASSERT_EQ(writeReg(edges, hw.ads1115_address, 3, 0x8000), 0);
  ASSERT_EQ(writeReg(edges, hw.ads1115_address, 2, 0x0000), 0);
  ASSERT_EQ(writeReg(edges, hw.ads1115_address, 1, std::uint16_t((5 << 12) | (1 << 9) | (7 << 5))), 0);
  int intermediate = 0;
  for (int i = 1; i <= 2000; ++i) {
    const TimeNs t = fromUs(2500) * i;
    if (i == 800) {  // the fine grid while the battery is off the bus, and back
      grid.plant().setBmsConnected(false);
      edges.plant().setBmsConnected(false);
    }
    if (i == 820) {
      grid.plant().setBmsConnected(true);
      edges.plant().setBmsConnected(true);
    }
    for (TimeNs e = edges.ads().nextReadyEdge(); e >= 0 && e < t; e = edges.ads().nextReadyEdge()) {
      edges.advanceTo(e);
      EXPECT_EQ(edges.now(), e);
      // The plant stays at the last grid point: the control grid, or the
      // 250 us grid while the battery is off the bus (the plant's truth
      // switches grids from the step after a BMS change: 800 and 820 are
      // transitions).
      if (i == 800 || i == 820) {
        EXPECT_LE(edges.plantTime(), e);
      } else {
        const bool fine = i > 800 && i < 820;
        EXPECT_EQ(edges.plantTime(), fine ? e - e % fromUs(250) : t - fromUs(2500));
      }
      ++intermediate;
    }
    grid.advanceTo(t);
    edges.advanceTo(t);
    ASSERT_EQ(edges.plantTime(), t);
    ASSERT_EQ(grid.truth().plant.battery_v, edges.truth().plant.battery_v) << "at step " << i;
    ASSERT_EQ(grid.truth().plant.alt_a, edges.truth().plant.alt_a) << "at step " << i;
    ASSERT_EQ(grid.truth().plant.soc_pct, edges.truth().plant.soc_pct) << "at step " << i;
  }
  EXPECT_GT(intermediate, 3000);  // ~2 ready edges per 2.5 ms
  EXPECT_GT(edges.ads().conversions(), 4000u);
  EXPECT_EQ(edges.ads().protocolErrors(), 0u);
}

// Noise is drawn per ADS1115 conversion (two conversions inside one plant
// step differ), never on a broken sense wire (exactly 0 V).
TEST(SimWorld, AdsNoiseIsPerConversion) {
  HardwareSettings hw;
  WorldConfig c;
  c.noise.alt_a = 2.0;  // 40 mV at the Hall output: hundreds of codes at +-4.096 V
  SimWorld w(c, hw);
  auto convert = [&](int mux) {
    writeReg(w, hw.ads1115_address, 1, std::uint16_t(0x8000 | (mux << 12) | (1 << 9) | 0x100 | (7 << 5) | 3));
    w.advanceTo(w.now() + fromUs(1200));  // one 860 SPS conversion, inside one plant step
    return std::int16_t(readReg(w, hw.ads1115_address, 0, 2));
  };
  w.advanceTo(fromUs(2500));
  const auto a = convert(5), b = convert(5);
  EXPECT_EQ(w.plantTime(), fromUs(2500));
  EXPECT_NE(a, b);
  w.setFault(Fault::battery_v_zero, true);
  EXPECT_EQ(convert(4), 0);
  EXPECT_EQ(convert(4), 0);
}

// The simulated DS18B20 file: at most one rewrite per 750 ms conversion, and
// a temperature fault reaches it at once.
TEST(SimWorld, OneWireFileRewrittenAtMostOncePerConversion) {
  HardwareSettings hw;
  WorldConfig c;
  c.noise.temp_f = 5.0;  // the value changes at every conversion
  c.w1Root = std::filesystem::temp_directory_path() / ("xr-world-w1-" + std::to_string(::getpid()));
  std::filesystem::remove_all(c.w1Root);
  {
    SimWorld w(c, hw);
    ASSERT_NE(w.onewire(), nullptr);
    const auto w0 = w.onewire()->writes();
    w.advanceTo(fromSec(60));
    const auto n = w.onewire()->writes() - w0;
    EXPECT_LE(n, 81u);  // 60 s / 750 ms, plus the one at t = 0
    EXPECT_GE(n, 60u);
    w.advanceTo(fromSec(60) + fromMs(100));
    w.setFault(Fault::temp_value, true, 212.0);  // 100 degC
    std::ifstream f(w.onewire()->slavePath());
    std::stringstream ss;
    ss << f.rdbuf();
    EXPECT_NE(ss.str().find("t=100000"), std::string::npos) << ss.str();
  }
  std::filesystem::remove_all(c.w1Root);
}

TEST(SimClock, MaxSpeedAdvancesVirtualTime) {
  HardwareSettings hw;
  SimWorld w(quiet(), hw);
  SimClock clk(w, 0.0);
  clk.sleepUntil(fromSec(3600));
  EXPECT_EQ(clk.now(), fromSec(3600));
  EXPECT_EQ(w.now(), fromSec(3600));
}

}  // namespace
}  // namespace xr::sim

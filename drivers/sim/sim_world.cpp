#include "drivers/sim/sim_world.h"

#include <algorithm>
#include <cmath>

#include "drivers/frontend/analog_frontend.h"

namespace xr::sim {
namespace {
constexpr double kAdsVdd = 5.0;  // ADS1115 supply on the board (inputs clamp at VDD + 0.3)
double fToC(double f) { return (f - 32.0) * 5.0 / 9.0; }
}  // namespace

SimWorld::SimWorld(const WorldConfig& cfg, const HardwareSettings& hw)
    : cfg_(cfg),
      hw_(hw),
      grid_(std::max<TimeNs>(cfg.maxStep, fromUs(1))),
      gridNext_(grid_),
      rng_(cfg.seed),
      plant_(cfg.plant),
      bus_(&now_),
      ads_(cfg.adsClockScale),
      pwm_(&now_),
      fieldEnable_(&now_),
      buzzer_(&now_),
      ignition_(true),
      watchdog_(&now_, fromSec(hw.watchdog_timeout_s)) {
  const auto& fe = hw_.frontend;
  ch0Gain_ = (fe.divider_r_top_ohm + fe.divider_r_bottom_ohm) / fe.divider_r_bottom_ohm;
  rpmScale_ = fe.rpm_per_volt / (fe.pulley_ratio > 0.0 ? fe.pulley_ratio : 1.0);
  // Noise at the ADS pins, in ADC volts, per conversion.
  pinSigma_ = {cfg_.noise.battery_v / ch0Gain_, cfg_.noise.alt_a * fe.hall_sensitivity_v_per_a,
               cfg_.noise.rpm / rpmScale_, 0.0};
  // The ADS1115 draws this noise itself, for the pin a conversion samples
  // (one channel per conversion), and clamps at the input protection.
  ads_.setInputNoise(&rng_, pinSigma_, kAdsVdd + 0.3);
  bus_.attach(hw.ina228_address, &ina_);
  bus_.attach(hw.ads1115_address, &ads_);
  if (!cfg.w1Root.empty()) w1_ = std::make_unique<SimOneWire>(cfg.w1Root);
  if (!cfg.w1Root.empty() && !cfg.batteryW1Id.empty())
    batteryW1_ = std::make_unique<SimOneWire>(cfg.w1Root, cfg.batteryW1Id);
  lm2907V_ = frontend::adcFromRpm(hw_.frontend, plant_.rpm());
  refreshAnalog(0.0);
  if (w1_) w1_->update(0, fToC(plant_.truth().alt_temp_f));
  if (batteryW1_) batteryW1_->update(0, plant_.truth().battery_temp_c);
}

SimWorld::~SimWorld() = default;

void SimWorld::setBmsChargeEnabled(bool en) noexcept { bmsLine_.setLevel(!en); }

void SimWorld::setFault(Fault f, bool active, double value) {
  faults_[int(f)] = active;
  faultValues_[int(f)] = active ? value : 0.0;
  switch (f) {
    case Fault::ina228_nack:
      bus_.setNack(hw_.ina228_address, active);
      break;
    case Fault::ads1115_nack:
      bus_.setNack(hw_.ads1115_address, active);
      break;
    case Fault::field_open:
      plant_.setFieldOpen(active);
      break;
    case Fault::belt_slip:
      plant_.setBeltSlip(active ? value : 0.0);
      break;
    case Fault::temp_sensor_disconnect:
      if (w1_) w1_->setPresent(!active);
      break;
    case Fault::temp_value:
      if (w1_) w1_->convertNow();  // the file follows the fault at once, not at the next 750 ms
      break;
    case Fault::battery_v_zero:  // a broken sense wire reads exactly 0 V, without noise
      ads_.setInputSigma(0, active ? 0.0 : pinSigma_[0]);
      break;
    case Fault::rpm_signal_loss:  // the tach ripple is noise only while there is a tach signal
      ads_.setInputSigma(2, active ? 0.0 : pinSigma_[2]);
      break;
    default:
      break;
  }
  refreshAnalog(0.0);
}

bool SimWorld::fieldGateEnabled() const noexcept {
  // GPIO4 drives the gate-driver enable; the INA228 ALERT (open drain) pulls
  // that same node low while active.
  const bool gpio = fieldEnable_.level() == hw_.field_enable_active_high;
  return gpio && !ina_.alertActive();
}

double SimWorld::fieldCommand() const noexcept { return fieldGateEnabled() ? pwm_.drive() : 0.0; }

SimTruth SimWorld::truth() const noexcept {
  SimTruth t;
  t.plant = plant_.truth();
  t.ina_alert = ina_.alertActive();
  t.field_on = fieldCommand() > 0.0 && !faults_[int(Fault::field_open)];
  return t;
}

void SimWorld::refreshAnalog(double dt) noexcept {
  const PlantTruth& p = plant_.truth();
  const NoiseConfig& n = cfg_.noise;
  const auto& fe = hw_.frontend;

  // INA228: low-side shunt carries the battery current; VBUS on battery +.
  Ina228Analog a;
  a.vshunt_v = (p.battery_a + rng_.gauss(n.bcur_a)) * hw_.shunt_resistance_ohm;
  a.vbus_v = std::max(0.0, p.battery_v + faultValues_[int(Fault::ibv_offset)] + rng_.gauss(n.ibv_v));
  a.dietemp_c = cfg_.inaDieTempC;
  ina_.setAnalog(a);

  // ADS1115 pins, noise-free: the model adds the noise when a conversion
  // actually samples a pin. (frontend::adcFromBatteryVolts / adcFromAltAmps /
  // adcFromRpm inlined, same arithmetic.)
  ads_.setInput(0, faults_[int(Fault::battery_v_zero)]
                       ? 0.0
                       : (p.battery_v + faultValues_[int(Fault::battery_v_offset)]) / ch0Gain_);
  const double hallA = p.alt_a + faultValues_[int(Fault::alt_current_offset)];
  ads_.setInput(1, fe.hall_zero_v + (fe.hall_invert ? -hallA : hallA) * fe.hall_sensitivity_v_per_a);
  // LM2907: tracks the tach frequency with a short ripple filter; when the
  // signal is lost its output decays through the 2 s coupling time constant.
  const bool lost = faults_[int(Fault::rpm_signal_loss)];
  // The tach is the alternator's own speed (its W terminal): a slipping belt slows it.
  const double target = lost ? 0.0 : std::max(0.0, plant_.tachRpm()) / rpmScale_;
  const double tau = lost ? 2.0 : 0.05;
  if (dt > 0.0) {
    if (dt != lagDt_ || tau != lagTau_) {
      lagDt_ = dt;
      lagTau_ = tau;
      lagK_ = 1.0 - std::exp(-dt / tau);
    }
    lm2907V_ += (target - lm2907V_) * lagK_;
  } else if (!lost) {
    lm2907V_ = target;
  }
  ads_.setInput(2, lm2907V_);
  // Temperatures move over seconds: refresh the thermistor node and the
  // 1-Wire reading every 50 ms of virtual time (and at once on a fault change).
  if (dt == 0.0 || now_ >= nextSlowRefresh_) {
    nextSlowRefresh_ = now_ + fromMs(50);
    double tempF = p.alt_temp_f + rng_.gauss(n.temp_f);
    if (faults_[int(Fault::temp_value)]) tempF = faultValues_[int(Fault::temp_value)];
    tempSenseF_ = tempF;
    // Open thermistor: the divider node sits at the supply.
    ch3V_ = faults_[int(Fault::temp_sensor_disconnect)] ? fe.thermistor_supply_v
                                                        : frontend::adcFromTempF(fe, tempF);
  }
  ads_.setInput(3, ch3V_);  // CH3: the thermistor node carries the temperature noise (slow refresh)

  if (w1_ && now_ >= w1_->nextConversion()) w1_->update(now_, fToC(tempSenseF_));
  if (batteryW1_ && now_ >= batteryW1_->nextConversion()) batteryW1_->update(now_, p.battery_temp_c);
}

void SimWorld::stepPlant(TimeNs to) noexcept {
  const double dt = toSec(to - plantNow_);
  plant_.step(fieldCommand(), dt);
  plantNow_ = to;
  if (to == gridNext_) gridNext_ += grid_;
  // (A grid point can lie before now() only when the battery left the bus
  // after an advance between grid points: the plant catches up, time does
  // not go back.)
  now_ = std::max(now_, to);
  refreshAnalog(dt);
  ina_.update(now_);  // the ALERT pin acts on the enable without any software
  ads_.update(now_);
}

void SimWorld::advanceStepping(TimeNs t) noexcept {
  for (;;) {
    // Finer steps while the battery is off the bus, so the INA228 ALERT
    // (BOVL) can act on the fast rise; a finer step never straddles a grid
    // point, so the grid is kept when the battery comes back.
    TimeNs next = gridNext_;
    if (!plant_.truth().bms_connected) next = std::min(next, plantNow_ + fromUs(250));
    if (next > t) break;
    stepPlant(next);
  }
  if (now_ < t) advanceChips(t);
}

}  // namespace xr::sim

#include "app/board_rig.h"

#include <cstring>
#include <stdexcept>

#include "runtime/fatal_guard.h"

namespace xr::app {

BoardRig::BoardRig(const Settings& settings) {
  const HardwareSettings& hw = settings.hardware;
  // GPIO first: the field enable is requested LOW before anything else.
  if (!gpio_.open(hw)) throw std::runtime_error("GPIO: " + gpio_.error());
  if (!pwm_.open(hw.pwm_sysfs_root, hw.pwm_chip, hw.pwm_channel, hw.pwm_frequency_hz, hw.pwm_inverted))
    throw std::runtime_error("PWM: " + pwm_.error());
  pwmSafe_ = pwm_.safeStateWriter();
  if (int e = bus_.open(hw.i2c_bus); e != 0)
    throw std::runtime_error("I2C: cannot open " + hw.i2c_bus + ": " + std::strerror(e) +
                             " (enable it with dtparam=i2c_arm=on in /boot/config.txt; run xregulatord --probe)");
  ina_ = std::make_unique<Ina228Driver>(bus_, hw.ina228_address, hw.shunt_resistance_ohm, hw.shunt_max_current_a);
  ads_ = std::make_unique<Ads1115Driver>(bus_, hw.ads1115_address, hw.ads_channel_sequence, hw.frontend, clock_,
                                         AdsPacing::SingleShot);
  sensors_ = std::make_unique<DriverSensors>(*ina_, *ads_);
  if (!watchdog_.open(hw.watchdog_device, hw.watchdog_timeout_s)) {
    watchdogWarning_ = "watchdog " + hw.watchdog_device + " not available: " + watchdog_.error();
  } else if (!watchdog_.warning().empty()) {
    watchdogWarning_ = watchdog_.warning();
  }
  ds18b20_ = std::make_unique<Ds18b20Reader>(hw.w1_root, hw.onewire_sensor_id);
  ds18b20_->start();
  if (!hw.vedirect_port.empty()) {
    vedirect_ = std::make_unique<VeDirectReader>(hw.vedirect_port);
    vedirect_->start();
  }
}

BoardRig::~BoardRig() {
  if (vedirect_) vedirect_->stop();
  if (ds18b20_) ds18b20_->stop();
}

rt::CycleDevices BoardRig::devices() {
  rt::CycleDevices d;
  d.sensors = sensors_.get();
  d.pwm = &pwm_;
  d.fieldEnable = gpio_.fieldEnable();
  d.buzzer = gpio_.buzzer();
  d.bms = gpio_.bms();
  d.ignition = gpio_.ignition();
  d.watchdog = watchdog_.isOpen() ? &watchdog_ : nullptr;
  d.hook = this;
  return d;
}

DriverSensors::StartReport BoardRig::startSensors(double bovlVolts) {
  pwm_.setDutyPercent(0.0);
  pwm_.setEnabled(true);  // the channel runs at duty 0; GPIO4 gates the field
  return sensors_->start(clock_.now(), bovlVolts);
}

void BoardRig::registerFatalActions() {
  // GPIO4 LOW first (gpiod_line_set_value is one ioctl), then the PWM.
  rt::fatal::addCallback(
      [](void* ctx) noexcept {
        if (auto* out = static_cast<GpioLibgpiod*>(ctx)->fieldEnable()) out->set(false);
      },
      &gpio_);
  rt::fatal::addCallback([](void* ctx) noexcept { static_cast<PwmSafeStateWriter*>(ctx)->driveSafe(); },
                         &pwmSafe_);
}

void BoardRig::beforeTick(TimeNs) {
  if (!handoffs_) return;
  // Relay the slow threads' lock-free samples into the cycle's hand-offs.
  const Ds18b20Sample s = ds18b20_->latest();
  rt::TemperatureHandoff th;
  th.tempF = s.stamp ? s.tempF : kNoValue;
  th.stamp = s.stamp;
  th.heartbeat = s.heartbeat;
  handoffs_->temperature.store(th);
  if (vedirect_) {
    const VeDirectSample v = vedirect_->latest();
    if (v.frames != lastVictronFrames_ && v.hasCurrent) {
      rt::VictronHandoff vh;
      vh.currentA = v.currentA;
      vh.voltageV = v.hasVoltage ? v.voltageV : kNoValue;
      vh.solarW = v.hasPpv ? v.ppvW : kNoValue;
      vh.stamp = v.stamp;
      handoffs_->victron.store(vh);
      lastVictronFrames_ = v.frames;
    }
  }
}

}  // namespace xr::app

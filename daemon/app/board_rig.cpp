#include "app/board_rig.h"

#include <cstring>
#include <stdexcept>

#include "runtime/ds18b20_handoff.h"
#include "runtime/fatal_guard.h"
#include "runtime/vedirect_handoff.h"

namespace xr::app {

namespace {
// ALERT/RDY as libgpiod line events, waited for on the control thread.
class LineReadyEdges final : public rt::ReadyEdgeSource {
 public:
  LineReadyEdges(AdsReadyLine& line, const Clock& clock) : line_(line), clock_(clock) {}
  int waitEdge(TimeNs deadline, TimeNs* stamp) noexcept override {
    // Stop waiting a little early: ppoll's relative timeout carries timer
    // slack (50 µs for a normal thread), and the loop's own
    // clock_nanosleep(TIMER_ABSTIME) hits the deadline itself. An edge in
    // the margin is serviced right after the tick (the driver's budget is
    // ~0.95 ms per edge).
    constexpr TimeNs kWakeMargin = 100'000;
    const TimeNs remaining = deadline - kWakeMargin - clock_.now();
    if (remaining <= 0) return 0;
    long long s = 0;
    const int rc = line_.wait(static_cast<long>(remaining), &s);
    if (rc != 1) return rc;
    // The kernel stamps events with CLOCK_MONOTONIC since Linux 5.7, the
    // loop clock's base. An older kernel stamps CLOCK_REALTIME: use the
    // wake-up time then (later than the edge by the wake-up latency).
    const TimeNs now = clock_.now();
    *stamp = (s > now || now - s > 1'000'000'000) ? now : static_cast<TimeNs>(s);
    return 1;
  }

 private:
  AdsReadyLine& line_;
  const Clock& clock_;
};
}  // namespace

BoardRig::BoardRig(const Settings& settings) {
  const HardwareSettings& hw = settings.hardware;
  // GPIO first: the field enable is requested LOW before anything else.
  if (!gpio_.open(hw)) throw std::runtime_error("GPIO: " + gpio_.error());
  if (!pwm_.open(hw.pwm_sysfs_root, hw.pwm_chip, hw.pwm_channel, hw.pwm_frequency_hz, hw.pwm_inverted))
    throw std::runtime_error("PWM: " + pwm_.error());
  pwmSafe_ = pwm_.safeStateWriter();
  if (int e = bus_.open(hw.i2c_bus); e != 0)
    throw std::runtime_error(
        "I2C: cannot open " + hw.i2c_bus + ": " + std::strerror(e) +
        " (enable it with dtparam=i2c_arm=on in /boot/config.txt; run xregulatord --probe)");
  // ADS1115 ALERT/RDY: ready-edge pacing (every conversion used) when the
  // line is configured and can be requested; single-shot pacing otherwise.
  bool readyEdges = false;
  if (hw.ads_alert_rdy_line >= 0) {
    if (readyLine_.open(hw.gpio_chip, hw.ads_alert_rdy_line)) {
      readyEdges = true;
      readyEdges_ = std::make_unique<LineReadyEdges>(readyLine_, clock_);
    } else {
      readyLineWarning_ = readyLine_.error() + ": ADS1115 falls back to single-shot pacing (CH1 ~200 Hz)";
    }
  }
  sensors_ = std::make_unique<DriverSensors>(bus_, hw, clock_, readyEdges);
  if (settings.pairing.button_line >= 0) {
    pairingButtonOpen_ = pairingButton_.open(hw.gpio_chip, settings.pairing.button_line);
    if (!pairingButtonOpen_)
      pairingButtonWarning_ = pairingButton_.error() + ": the pairing button is ignored";
  }
  if (!watchdog_.open(hw.watchdog_device, hw.watchdog_timeout_s)) {
    watchdogWarning_ = "watchdog " + hw.watchdog_device + " not available: " + watchdog_.error();
  } else if (!watchdog_.warning().empty()) {
    watchdogWarning_ = watchdog_.warning();
  }
  ds18b20_ = std::make_unique<Ds18b20Reader>(hw.w1_root, hw.onewire_sensor_id);
  ds18b20_->excludeId(hw.battery_temp_sensor);
  if (!hw.battery_temp_sensor.empty()) {
    batteryDs18b20_ = std::make_unique<Ds18b20Reader>(hw.w1_root, hw.battery_temp_sensor);
  }
  if (!hw.vedirect_port.empty()) vedirect_ = std::make_unique<VeDirectReader>(hw.vedirect_port);
}

BoardRig::~BoardRig() {
  if (vedirect_) vedirect_->stop();
  if (batteryDs18b20_) batteryDs18b20_->stop();
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
  d.adsReady = readyEdges_.get();
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

void BoardRig::attach(rt::Handoffs& h) {
  // One hand-off per reading: the reader thread stores it where the cycle
  // reads it (docs/architecture.md "Threads").
  ds18b20_->onSample([&h](const Ds18b20Sample& s) { h.temperature.store(temperatureHandoff(s)); });
  ds18b20_->start();
  if (batteryDs18b20_) {
    // Source ds18b20 from the start, before the first reading, so the core
    // knows a probe is expected (docs/batteries.md).
    h.batteryTemp.store(batteryTempHandoff(Ds18b20Sample{}));
    batteryDs18b20_->onSample([&h](const Ds18b20Sample& s) { h.batteryTemp.store(batteryTempHandoff(s)); });
    batteryDs18b20_->start();
  }
  if (vedirect_) {
    vedirect_->onSample([&h](const VeDirectSample& s) { postVeDirect(h, s); });
    vedirect_->start();
  }
}

}  // namespace xr::app

#pragma once
// The real board: i2c-dev, sysfs PWM, libgpiod lines, /dev/watchdog,
// DS18B20 (w1 sysfs, 1 Hz thread) and VE.Direct (serial thread), with the
// same drivers and control cycle as the simulation. Throws
// std::runtime_error naming what to fix when a required device is missing.
#include <memory>

#include "config/settings.h"
#include "drivers/gpio/gpio_button.h"
#include "drivers/gpio/gpio_libgpiod.h"
#include "drivers/i2c/linux_i2c_bus.h"
#include "drivers/onewire/ds18b20_reader.h"
#include "drivers/pwm/pwm_sysfs.h"
#include "drivers/vedirect/vedirect_reader.h"
#include "drivers/watchdog/linux_watchdog.h"
#include "runtime/driver_sensors.h"
#include "runtime/handoffs.h"
#include "runtime/monotonic_clock.h"

namespace xr::app {

class BoardRig final {
 public:
  explicit BoardRig(const Settings& settings);
  ~BoardRig();
  rt::CycleDevices devices();
  Clock& loopClock() { return clock_; }
  rt::MonotonicClock& wall() { return clock_; }
  DriverSensors::StartReport startSensors(double bovlVolts);
  // The hand-offs the cycle reads; starts the DS18B20 and VE.Direct
  // readers, which write their samples into them from their own threads.
  void attach(rt::Handoffs& h);
  // Async-signal-safe fatal actions: PWM duty 0 + enable 0 via the
  // pre-opened sysfs descriptors, GPIO4 LOW via its requested line.
  void registerFatalActions();
  const std::string& watchdogWarning() const { return watchdogWarning_; }
  const std::string& readyLineWarning() const { return readyLineWarning_; }
  // [pairing] button_line, when set and requested; null otherwise (and
  // pairingButtonWarning() says why: a missing button never stops charging).
  ButtonInput* pairingButton() { return pairingButtonOpen_ ? &pairingButton_ : nullptr; }
  const std::string& pairingButtonWarning() const { return pairingButtonWarning_; }

 private:
  rt::MonotonicClock clock_;
  LinuxI2cBus bus_;
  std::unique_ptr<DriverSensors> sensors_;
  AdsReadyLine readyLine_;
  std::unique_ptr<rt::ReadyEdgeSource> readyEdges_;
  PwmSysfs pwm_;
  PwmSafeStateWriter pwmSafe_;
  GpioLibgpiod gpio_;
  LinuxWatchdog watchdog_;
  std::string watchdogWarning_;
  std::string readyLineWarning_;
  GpioButtonLine pairingButton_;
  bool pairingButtonOpen_ = false;
  std::string pairingButtonWarning_;
  std::unique_ptr<Ds18b20Reader> ds18b20_;
  std::unique_ptr<Ds18b20Reader> batteryDs18b20_;  // [hardware] battery_temp_sensor (docs/batteries.md)
  std::unique_ptr<VeDirectReader> vedirect_;
};

}  // namespace xr::app

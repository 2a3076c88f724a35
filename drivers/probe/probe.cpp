#include "drivers/probe/probe.h"

#include <fcntl.h>
#include <gpiod.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>

#include "drivers/ads1115/ads1115_registers.h"
#include "drivers/i2c/i2c_registers.h"
#include "drivers/i2c/linux_i2c_bus.h"
#include "drivers/ina228/ina228_registers.h"
#include "drivers/onewire/w1_therm.h"
#include "drivers/vedirect/vedirect_reader.h"

namespace xr {

namespace {

class Report {
 public:
  explicit Report(std::ostream& out) : out_(out) {}
  void ok(const std::string& what) { out_ << "[ OK ] " << what << "\n"; }
  void warn(const std::string& what, const std::string& fix) {
    ++warnings_;
    out_ << "[WARN] " << what << "\n";
    if (!fix.empty()) out_ << "       fix: " << fix << "\n";
  }
  void fail(const std::string& what, const std::string& fix) {
    ++failures_;
    out_ << "[FAIL] " << what << "\n";
    if (!fix.empty()) out_ << "       fix: " << fix << "\n";
  }
  int failures() const { return failures_; }
  int warnings() const { return warnings_; }

 private:
  std::ostream& out_;
  int failures_ = 0, warnings_ = 0;
};

std::string hex(unsigned v, int width) {
  char b[16];
  std::snprintf(b, sizeof b, "0x%0*X", width, v);
  return b;
}
std::string err(int e) { return std::string(std::strerror(e)) + " (errno " + std::to_string(e) + ")"; }
bool exists(const std::string& p) {
  struct stat st;
  return ::stat(p.c_str(), &st) == 0;
}
constexpr const char* kConfigTxt = "/boot/firmware/config.txt (/boot/config.txt on older images)";

void probeChips(const HardwareSettings& hw, I2cBus& bus, Report& r) {
  // INA228: identify by MANUFACTURER_ID and DEVICE_ID (read-only registers).
  std::uint16_t mfr = 0, dev = 0;
  int rc = i2creg::readReg16(bus, hw.ina228_address, ina228::MANUFACTURER_ID, &mfr);
  if (rc == 0) rc = i2creg::readReg16(bus, hw.ina228_address, ina228::DEVICE_ID, &dev);
  const std::string inaAt = "INA228 at " + hex(hw.ina228_address, 2);
  if (rc != 0) {
    r.fail(inaAt + ": no answer: " + err(rc),
           "check the INA228 wiring (SDA/SCL/VS/GND) and its A0/A1 straps; set [hardware] ina228_address "
           "(0x40-0x4F); 'i2cdetect -y 1' lists the answering addresses");
  } else if (mfr != ina228::kManufacturerTI || ((dev >> 4) & 0xFFF) != ina228::kDieId) {
    r.fail(inaAt + ": a different chip answers (MANUFACTURER_ID " + hex(mfr, 4) + ", DEVICE_ID " +
               hex(dev, 4) + ")",
           "expected MANUFACTURER_ID 0x5449 and DEVICE_ID 0x228x; check [hardware] ina228_address");
  } else {
    r.ok(inaAt + " (MANUFACTURER_ID " + hex(mfr, 4) + ", DEVICE_ID " + hex(dev, 4) + ")");
  }
  // ADS1115 has no ID register: the Config register must answer with a
  // plausible value (bits 7:5 DR, 1:0 COMP_QUE are free; the read is harmless).
  std::uint16_t cfg = 0;
  rc = i2creg::readReg16(bus, hw.ads1115_address, ads1115::CONFIG, &cfg);
  const std::string adsAt = "ADS1115 at " + hex(hw.ads1115_address, 2);
  if (rc != 0) {
    r.fail(adsAt + ": no answer: " + err(rc),
           "check the ADS1115 wiring and its ADDR pin (GND 0x48, VDD 0x49, SDA 0x4A, SCL 0x4B); set "
           "[hardware] ads1115_address");
  } else {
    r.ok(adsAt + " (Config " + hex(cfg, 4) + ")");
  }
}

void probePwm(const HardwareSettings& hw, Report& r) {
  const std::string chip = hw.pwm_sysfs_root + "/pwmchip" + std::to_string(hw.pwm_chip);
  if (!exists(chip)) {
    r.fail("PWM chip " + chip + " not found",
           std::string("add 'dtoverlay=pwm,pin=18,func=2' to ") + kConfigTxt + " and reboot");
    return;
  }
  const std::string ch = chip + "/pwm" + std::to_string(hw.pwm_channel);
  if (exists(ch)) {
    if (::access((ch + "/duty_cycle").c_str(), W_OK) != 0) {
      r.fail("PWM " + ch + " exported but not writable: " + err(errno),
             "run as root or add the service user to the 'gpio' group (udev rule in systemd/)");
      return;
    }
    r.ok("PWM " + ch + " (exported, writable)");
    return;
  }
  if (::access((chip + "/export").c_str(), W_OK) != 0) {
    r.fail("PWM " + chip + "/export not writable: " + err(errno),
           "run as root or add the service user to the 'gpio' group");
    return;
  }
  r.ok("PWM " + chip + " (channel " + std::to_string(hw.pwm_channel) + " will be exported at start)");
}

void probeGpio(const HardwareSettings& hw, Report& r) {
  gpiod_chip* chip = gpiod_chip_open_lookup(hw.gpio_chip.c_str());
  if (!chip) {
    const int e = errno;
    r.fail("GPIO chip " + hw.gpio_chip + ": " + err(e),
           e == EACCES ? "add the service user to the 'gpio' group"
                       : "check [hardware] gpio_chip ('gpiodetect' lists the chips; the 40-pin header is "
                         "gpiochip0, or gpiochip4 on a Raspberry Pi 5 with older kernels)");
    return;
  }
  auto line = [&](int offset, const char* what, bool required) {
    if (offset < 0) {
      r.ok(std::string(what) + ": not wired (disabled in config)");
      return;
    }
    gpiod_line* l = gpiod_chip_get_line(chip, static_cast<unsigned>(offset));
    const std::string name =
        std::string(what) + " (" + hw.gpio_chip + " line " + std::to_string(offset) + ")";
    if (!l) {
      if (required)
        r.fail(name + ": no such line", "check the line number in [hardware]");
      else
        r.warn(name + ": no such line", "check the line number in [hardware]");
      return;
    }
    gpiod_line_update(l);
    if (gpiod_line_is_used(l)) {
      const char* c = gpiod_line_consumer(l);
      const std::string who = c ? c : "?";
      if (who == "xregulatord") {
        r.ok(name + ": held by a running xregulatord");
      } else {
        const std::string msg = name + ": in use by '" + who + "'";
        const std::string fix = "free the line (remove the overlay or program using it; 'gpioinfo' shows it)";
        if (required)
          r.fail(msg, fix);
        else
          r.warn(msg, fix);
      }
      return;
    }
    r.ok(name + ": free");
  };
  line(hw.field_enable_line, "field enable", true);
  line(hw.buzzer_line, "buzzer", false);
  line(hw.bms_line, "BMS input", false);
  line(hw.ignition_line, "ignition input", false);
  line(hw.ads_alert_rdy_line, "ADS1115 ALERT/RDY", false);
  gpiod_chip_close(chip);
}

void probeWatchdog(const HardwareSettings& hw, Report& r) {
  // Never open it here: opening /dev/watchdog arms it.
  if (!exists(hw.watchdog_device)) {
    r.warn("watchdog " + hw.watchdog_device + " not found (the daemon runs without a hardware watchdog)",
           std::string("add 'dtparam=watchdog=on' to ") + kConfigTxt);
    return;
  }
  if (::access(hw.watchdog_device.c_str(), W_OK) != 0) {
    r.warn(
        "watchdog " + hw.watchdog_device + " not writable: " + err(errno),
        "run the service as root or grant it access (systemd unit); make sure systemd's RuntimeWatchdogSec "
        "does not hold it");
    return;
  }
  r.ok("watchdog " + hw.watchdog_device);
}

void probeOneWire(const HardwareSettings& hw, Report& r) {
  const auto sensors = w1::listDs18b20(hw.w1_root);
  const std::string fix =
      std::string("add 'dtoverlay=w1-gpio,gpiopin=<pin>' to ") + kConfigTxt +
      " (not GPIO4: it is the field enable here), wire DS18B20 data with a 4.7 kΩ pull-up";
  if (sensors.empty() && !hw.onewire_sensor_id.empty()) {
    r.fail(
        "1-Wire sensor " + hw.onewire_sensor_id + " (configured) not present: no DS18B20 under " + hw.w1_root,
        fix);
    return;
  }
  if (sensors.empty()) {
    r.warn("1-Wire: no DS18B20 (28-*) under " + hw.w1_root +
               " (alternator temperature from the thermistor only)",
           fix);
    return;
  }
  for (const auto& id : sensors) {
    std::string text;
    if (FILE* f = std::fopen((hw.w1_root + "/" + id + "/w1_slave").c_str(), "r")) {
      char buf[256];
      const std::size_t n = std::fread(buf, 1, sizeof buf, f);
      std::fclose(f);
      text.assign(buf, n);
    }
    const auto rd = w1::parseW1Slave(text);
    if (rd.error == w1::ParseError::None) {
      char t[32];
      std::snprintf(t, sizeof t, "%.2f °F", rd.milliC / 1000.0 * 9.0 / 5.0 + 32.0);
      r.ok("1-Wire " + id + ": " + t);
    } else {
      r.warn("1-Wire " + id + ": " + w1::toString(rd.error), "check the sensor wiring and the pull-up");
    }
  }
  if (!hw.onewire_sensor_id.empty()) {
    bool found = false;
    for (const auto& id : sensors) found = found || id == hw.onewire_sensor_id;
    if (!found) r.fail("1-Wire sensor " + hw.onewire_sensor_id + " (configured) not present", fix);
  }
}

void probeSerial(const HardwareSettings& hw, Report& r) {
  if (hw.vedirect_port.empty()) {
    r.ok("VE.Direct: not configured");
    return;
  }
  const int fd = ::open(hw.vedirect_port.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    const int e = errno;
    r.fail("VE.Direct port " + hw.vedirect_port + ": " + err(e),
           e == EACCES
               ? "add the service user to the 'dialout' group"
               : "plug in the VE.Direct USB cable or fix [hardware] vedirect_port (ls /dev/serial/by-id/)");
    return;
  }
  const int rc = configureVeDirectTty(fd);
  ::close(fd);
  if (rc != 0) {
    r.fail("VE.Direct port " + hw.vedirect_port + " is not a serial port: " + err(rc),
           "point [hardware] vedirect_port at the tty of the VE.Direct cable");
    return;
  }
  r.ok("VE.Direct port " + hw.vedirect_port + " (19200 8N1)");
}

void probeI2cClock(const HardwareSettings& hw, Report& r) {
  const unsigned long hz = readI2cClockHz(hw.i2c_bus);
  if (hz == 0) return;  // not a device-tree adapter: nothing to say
  if (hz < 400000) {
    r.warn("I2C bus clock " + std::to_string(hz / 1000) +
               " kHz: INA228 + ADS1115 reads take most of a 2.5 ms tick",
           std::string("add 'dtparam=i2c_arm_baudrate=400000' to ") + kConfigTxt + " and reboot");
  } else {
    r.ok("I2C bus clock " + std::to_string(hz / 1000) + " kHz");
  }
}

}  // namespace

unsigned long readI2cClockHz(const std::string& devPath, const std::string& sysRoot) {
  const auto slash = devPath.find_last_of('/');
  const std::string name = slash == std::string::npos ? devPath : devPath.substr(slash + 1);
  const std::string p = sysRoot + "/class/i2c-dev/" + name + "/device/of_node/clock-frequency";
  FILE* f = std::fopen(p.c_str(), "rb");
  if (!f) return 0;
  unsigned char b[4] = {};
  const std::size_t n = std::fread(b, 1, 4, f);
  std::fclose(f);
  if (n != 4) return 0;
  return (static_cast<unsigned long>(b[0]) << 24) | (static_cast<unsigned long>(b[1]) << 16) |
         (static_cast<unsigned long>(b[2]) << 8) | b[3];
}

int runProbe(const Settings& settings, std::ostream& out) { return runProbe(settings, out, nullptr); }

int runProbe(const Settings& settings, std::ostream& out, I2cBus* busOverride) {
  const HardwareSettings& hw = settings.hardware;
  Report r(out);
  out << "xregulatord hardware probe\n";
  if (busOverride) {
    r.ok("I2C bus (provided)");
    probeChips(hw, *busOverride, r);
  } else {
    LinuxI2cBus bus;
    const int rc = bus.open(hw.i2c_bus);
    if (rc == ENOENT) {
      r.fail("I2C bus " + hw.i2c_bus + " not found",
             std::string("add 'dtparam=i2c_arm=on' to ") + kConfigTxt +
                 " and reboot (or 'sudo raspi-config nonint do_i2c 0'); check [hardware] i2c_bus");
    } else if (rc == EACCES) {
      r.fail("I2C bus " + hw.i2c_bus + ": permission denied", "add the service user to the 'i2c' group");
    } else if (rc != 0) {
      r.fail("I2C bus " + hw.i2c_bus + " is not a usable i2c-dev adapter: " + err(rc),
             "point [hardware] i2c_bus at /dev/i2c-N ('i2cdetect -l' lists them)");
    } else {
      r.ok("I2C bus " + hw.i2c_bus);
      probeI2cClock(hw, r);
      probeChips(hw, bus, r);
    }
  }
  probePwm(hw, r);
  probeGpio(hw, r);
  probeWatchdog(hw, r);
  probeOneWire(hw, r);
  probeSerial(hw, r);
  if (r.failures() == 0) {
    out << "Result: ready (" << r.warnings() << " warning(s)).\n";
    return 0;
  }
  out << "Result: " << r.failures() << " required item(s) missing; fix them and run --probe again.\n";
  return 1;
}

}  // namespace xr

#include "config/settings_schema.h"

#include <array>
#include <cmath>

#include "config/format.h"

namespace xr {
namespace {

// One entry per Settings field. The member expression appears once; the
// lambdas convert between the field's C++ type and a SettingValue.
#define XR_S_STR(tbl, member, key, choices, help)                                       \
  SettingSpec {                                                                         \
    tbl, key, SettingKind::String, "", 0, 0, choices, false, help,                      \
        [](const Settings& s) -> SettingValue { return s.member; },                     \
        [](Settings& s, const SettingValue& v) { s.member = std::get<std::string>(v); } \
  }
#define XR_S_INT(tbl, member, key, unit, lo, hi, hex, help)                                    \
  SettingSpec {                                                                                \
    tbl, key, SettingKind::Int, unit, lo, hi, "", hex, help,                                   \
        [](const Settings& s) -> SettingValue { return static_cast<std::int64_t>(s.member); }, \
        [](Settings& s, const SettingValue& v) {                                               \
          s.member = static_cast<decltype(s.member)>(std::get<std::int64_t>(v));               \
        }                                                                                      \
  }
#define XR_S_FLT(tbl, member, key, unit, lo, hi, help)                                   \
  SettingSpec {                                                                          \
    tbl, key, SettingKind::Float, unit, lo, hi, "", false, help,                         \
        [](const Settings& s) -> SettingValue { return static_cast<double>(s.member); }, \
        [](Settings& s, const SettingValue& v) { s.member = std::get<double>(v); }       \
  }
#define XR_S_BOOL(tbl, member, key, help)                                        \
  SettingSpec {                                                                  \
    tbl, key, SettingKind::Bool, "", 0, 1, "", false, help,                      \
        [](const Settings& s) -> SettingValue { return s.member; },              \
        [](Settings& s, const SettingValue& v) { s.member = std::get<bool>(v); } \
  }

const SettingSpec kSchema[] = {
    // [hardware]
    XR_S_STR("hardware", hardware.i2c_bus, "i2c_bus", "", "I2C bus device the INA228 and ADS1115 sit on."),
    XR_S_INT("hardware", hardware.ina228_address, "ina228_address", "", 0x03, 0x77, true,
             "INA228 7-bit I2C address (A0/A1 strapping; 0x40 with both to GND)."),
    XR_S_INT("hardware", hardware.ads1115_address, "ads1115_address", "", 0x03, 0x77, true,
             "ADS1115 7-bit I2C address (0x48 with ADDR to GND)."),
    XR_S_FLT("hardware", hardware.shunt_resistance_ohm, "shunt_resistance_ohm", "ohm", 1e-6, 10.0,
             "Battery shunt resistance on the INA228 (500 uOhm = 100 A at 50 mV)."),
    XR_S_FLT("hardware", hardware.shunt_max_current_a, "shunt_max_current_a", "A", 1.0, 10000.0,
             "Largest expected battery current; sets the INA228 CURRENT_LSB = max / 2^19."),
    SettingSpec{"hardware", "ads_channel_sequence", SettingKind::IntList, "", 0, 3, "", false,
                "ADS1115 channels converted in turn (CH0 battery V, CH1 alternator current, CH2 RPM, CH3 "
                "thermistor); repeating CH1 gives the current loop fresher samples.",
                [](const Settings& s) -> SettingValue {
                  return std::vector<std::int64_t>(s.hardware.ads_channel_sequence.begin(),
                                                   s.hardware.ads_channel_sequence.end());
                },
                [](Settings& s, const SettingValue& v) {
                  const auto& l = std::get<std::vector<std::int64_t>>(v);
                  s.hardware.ads_channel_sequence.assign(l.begin(), l.end());
                }},
    XR_S_INT("hardware", hardware.ads_alert_rdy_line, "ads_alert_rdy_line", "", -1, 1023, false,
             "GPIO line of the ADS1115 ALERT/RDY pin: every conversion is used, CH1 ~430 Hz (-1 = not wired: "
             "single-shot, ~200 Hz; a configured line with no edges is retried once, then falls back to "
             "single-shot after 500 ms)."),
    XR_S_STR("hardware", hardware.pwm_sysfs_root, "pwm_sysfs_root", "", "sysfs PWM class directory."),
    XR_S_INT("hardware", hardware.pwm_chip, "pwm_chip", "", 0, 63, false,
             "pwmchipN driving the field (dtoverlay=pwm,pin=18,func=2 gives pwmchip0)."),
    XR_S_INT("hardware", hardware.pwm_channel, "pwm_channel", "", 0, 15, false, "PWM channel on that chip."),
    XR_S_FLT("hardware", hardware.pwm_frequency_hz, "pwm_frequency_hz", "Hz", 1.0, 100000.0,
             "Field PWM frequency."),
    XR_S_BOOL("hardware", hardware.pwm_inverted, "pwm_inverted",
              "Invert the PWM polarity (driver stage inverts)."),
    XR_S_STR("hardware", hardware.gpio_chip, "gpio_chip", "", "GPIO chip (libgpiod name or /dev path)."),
    XR_S_INT("hardware", hardware.field_enable_line, "field_enable_line", "", 0, 1023, false,
             "Field driver hard enable (GPIO4 on the upstream board). Also wire the INA228 ALERT to it."),
    XR_S_BOOL("hardware", hardware.field_enable_active_high, "field_enable_active_high",
              "true: HIGH enables the field (the specification: GPIO4 HIGH = enabled)."),
    XR_S_INT("hardware", hardware.buzzer_line, "buzzer_line", "", -1, 1023, false,
             "Alarm buzzer output (GPIO21 upstream; -1 = none)."),
    XR_S_INT("hardware", hardware.bms_line, "bms_line", "", -1, 1023, false,
             "BMS charge-disable input (-1 = not wired)."),
    XR_S_BOOL("hardware", hardware.bms_active_low, "bms_active_low",
              "true: a LOW BMS input means charging is disabled (the specification: bmsLogicLevelOff)."),
    XR_S_INT("hardware", hardware.ignition_line, "ignition_line", "", -1, 1023, false,
             "Ignition input (-1 = not wired, treated as on)."),
    XR_S_BOOL("hardware", hardware.ignition_active_low, "ignition_active_low",
              "true: LOW means ignition on."),
    XR_S_STR("hardware", hardware.watchdog_device, "watchdog_device", "",
             "Hardware watchdog device (empty = do not use the hardware watchdog)."),
    XR_S_INT("hardware", hardware.watchdog_timeout_s, "watchdog_timeout_s", "s", 1, 255, false,
             "Hardware watchdog timeout (the specification: 16 s)."),
    XR_S_STR("hardware", hardware.w1_root, "w1_root", "", "1-Wire sysfs devices directory."),
    XR_S_STR("hardware", hardware.onewire_sensor_id, "onewire_sensor_id", "",
             "DS18B20 id (\"28-...\"); empty = the first one found."),
    XR_S_STR("hardware", hardware.battery_temp_sensor, "battery_temp_sensor", "",
             "Battery DS18B20 id (\"28-...\") on the same 1-Wire bus; empty = no battery temperature sensor "
             "(docs/batteries.md). Set onewire_sensor_id too when two sensors are wired. The set-up page's "
             "choice, when one was made, replaces this from the next start (docs/configuration.md)."),
    XR_S_STR("hardware", hardware.vedirect_port, "vedirect_port", "",
             "VE.Direct serial port (e.g. /dev/ttyUSB0); empty = none."),
    // [hardware.frontend]
    XR_S_FLT("hardware.frontend", hardware.frontend.divider_r_top_ohm, "divider_r_top_ohm", "ohm", 1.0, 1e9,
             "CH0 battery voltage divider, upper resistor."),
    XR_S_FLT("hardware.frontend", hardware.frontend.divider_r_bottom_ohm, "divider_r_bottom_ohm", "ohm", 1.0,
             1e9, "CH0 battery voltage divider, lower resistor."),
    XR_S_FLT("hardware.frontend", hardware.frontend.hall_zero_v, "hall_zero_v", "V", 0.0, 5.0,
             "CH1 Hall sensor output at 0 A."),
    XR_S_FLT("hardware.frontend", hardware.frontend.hall_sensitivity_v_per_a, "hall_sensitivity_v_per_a",
             "V/A", 1e-5, 10.0, "CH1 Hall sensor sensitivity."),
    XR_S_BOOL("hardware.frontend", hardware.frontend.hall_invert, "hall_invert",
              "Hall sensor mounted the other way round."),
    XR_S_FLT("hardware.frontend", hardware.frontend.rpm_per_volt, "rpm_per_volt", "RPM/V", 0.001, 1e6,
             "CH2 LM2907 tach output scaling."),
    XR_S_FLT("hardware.frontend", hardware.frontend.pulley_ratio, "pulley_ratio", "", 0.01, 100.0,
             "Alternator/crank pulley ratio (1 = already folded into rpm_per_volt)."),
    XR_S_FLT("hardware.frontend", hardware.frontend.rpm_low_floor, "rpm_low_floor", "RPM", 0.0, 10000.0,
             "Below this the RPM reading is 0 (LM2907 offset)."),
    XR_S_FLT("hardware.frontend", hardware.frontend.thermistor_beta, "thermistor_beta", "K", 100.0, 100000.0,
             "CH3 thermistor beta."),
    XR_S_FLT("hardware.frontend", hardware.frontend.thermistor_r0_ohm, "thermistor_r0_ohm", "ohm", 1.0, 1e9,
             "CH3 thermistor resistance at thermistor_t0_c."),
    XR_S_FLT("hardware.frontend", hardware.frontend.thermistor_t0_c, "thermistor_t0_c", "degC", -50.0, 200.0,
             "CH3 thermistor reference temperature."),
    XR_S_FLT("hardware.frontend", hardware.frontend.thermistor_series_r_ohm, "thermistor_series_r_ohm", "ohm",
             1.0, 1e9, "CH3 series resistor."),
    XR_S_FLT("hardware.frontend", hardware.frontend.thermistor_supply_v, "thermistor_supply_v", "V", 0.1,
             30.0, "CH3 divider supply."),
    // [runtime]
    XR_S_INT("runtime", runtime.control_period_us, "control_period_us", "us", 500, 100000, false,
             "Control tick period (2500 us = 400 Hz)."),
    XR_S_INT("runtime", runtime.rt_priority, "rt_priority", "", 1, 99, false,
             "SCHED_FIFO priority of the control thread."),
    XR_S_INT("runtime", runtime.cpu, "cpu", "", -1, 1023, false,
             "Pin the control thread to this CPU (-1 = no pinning)."),
    // [web]
    XR_S_STR("web", web.listen, "listen", "",
             "HTTP listen address (0.0.0.0 = the boat's network: reads open, writes only from paired phones; "
             "127.0.0.1 = this machine only)."),
    XR_S_INT("web", web.port, "port", "", 1, 65535, false, "HTTP port."),
    XR_S_STR("web", web.token, "token", "",
             "Bearer token for writes; empty = generated at first start and kept with the state."),
    XR_S_FLT("web", web.telemetry_rate_hz, "telemetry_rate_hz", "Hz", 0.1, 100.0,
             "WebSocket telemetry rate."),
    XR_S_BOOL("web", web.reads_require_token, "reads_require_token", "Require the token for reads too."),
    XR_S_INT("web", web.max_connections, "max_connections", "", 1, 10000, false,
             "Simultaneous HTTP/WebSocket clients."),
    XR_S_STR("web", web.www_root, "www_root", "",
             "Dashboard assets directory; empty = the packaged /usr/share/xregulator/www."),
    // [store]
    XR_S_STR("store", store.path, "path", "", "SQLite state database (overridden by --state-db)."),
    XR_S_INT("store", store.checkpoint_interval_s, "checkpoint_interval_s", "s", 1, 86400, false,
             "How often state (SoC, energy, learned values) is checkpointed."),
    // [can] (beside the Bms* parameters of the same table)
    XR_S_STR(
        "can", can.bms_interface, "bms_interface", "",
        "SocketCAN interface of the BMS bus (500 kbit/s, 11-bit frames), e.g. can0; empty = no BMS on CAN. "
        "A BMS set here is obeyed (its CVL, CCL, charge-disable and warnings; stale after BmsStaleS of "
        "silence); BmsLimitsEnabled = 0 makes it monitor only. The set-up page's choice, when one was made, "
        "replaces this from the next start (docs/configuration.md)."),
    XR_S_STR(
        "can", can.bms_protocol, "bms_protocol", "victron,pylontech,rec",
        "What the BMS speaks: victron (the 0x351/0x355/0x356/0x35A/0x35E set most LFP BMSs and Victron GX "
        "devices send), pylontech (the same set with Pylontech's 0x359 protection and warning flags), rec "
        "(REC BMS: the same set with the highest cell voltage in 0x373, for BmsCellHighV)."),
    XR_S_STR(
        "can", can.n2k_interface, "n2k_interface", "",
        "SocketCAN interface of the NMEA 2000 bus (250 kbit/s, 29-bit); empty = no NMEA 2000. Our node "
        "publishes battery and charger status there (docs/integrations.md); --sim uses its simulated bus."),
    XR_S_INT("can", can.n2k_preferred_address, "n2k_preferred_address", "", 0, 251, false,
             "NMEA 2000 source address claimed first (ISO 11783-5 address claim, PGN 60928); moved on a "
             "conflict."),
    XR_S_STR(
        "can", can.RpmSource, "RpmSource", "tach,n2k",
        "Where RPM comes from: tach (ADS1115 CH2, the W terminal or the stator) or n2k (engine speed from "
        "PGN 127488 or J1939 61444 on the NMEA 2000 bus, engine instance 0, for engines without a W "
        "terminal; needs n2k_interface). An ECU silent for 1 s reads 0 rpm, as a tach with no pulses does."),
    // [log]
    XR_S_STR("log", log.level, "level", "trace,debug,info,warn,error,critical,off",
             "Log level (overridden by --log-level)."),
    // [integrations.signalk] (docs/integrations.md)
    XR_S_BOOL("integrations.signalk", integrations.signalk.enabled, "enabled",
              "Send deltas to a Signal K server."),
    XR_S_STR("integrations.signalk", integrations.signalk.url, "url", "",
             "Signal K WebSocket stream (ws://host:3000/signalk/v1/stream?subscribe=none)."),
    XR_S_FLT("integrations.signalk", integrations.signalk.rate_hz, "rate_hz", "Hz", 0.1, 10.0,
             "Deltas per second; a change of mode or stage goes at once."),
    XR_S_STR("integrations.signalk", integrations.signalk.alternator_id, "alternator_id", "",
             "<id> in electrical.alternators.<id> (letters and digits)."),
    XR_S_STR("integrations.signalk", integrations.signalk.battery_id, "battery_id", "",
             "<id> in electrical.batteries.<id> (letters and digits)."),
    // [integrations.mqtt]
    XR_S_BOOL("integrations.mqtt", integrations.mqtt.enabled, "enabled",
              "Publish to Home Assistant through MQTT discovery."),
    XR_S_STR("integrations.mqtt", integrations.mqtt.host, "host", "", "MQTT broker host."),
    XR_S_INT("integrations.mqtt", integrations.mqtt.port, "port", "", 1, 65535, false,
             "MQTT broker port (1883; 8883 with TLS)."),
    XR_S_STR("integrations.mqtt", integrations.mqtt.username, "username", "",
             "MQTT user name (empty = none)."),
    XR_S_STR("integrations.mqtt", integrations.mqtt.password, "password", "", "MQTT password."),
    XR_S_STR("integrations.mqtt", integrations.mqtt.discovery_prefix, "discovery_prefix", "",
             "Home Assistant discovery prefix."),
    XR_S_STR("integrations.mqtt", integrations.mqtt.node_id, "node_id", "",
             "<id> in xregulator_<id> and xregulator/<id>/state (letters, digits, _ and -)."),
    XR_S_FLT("integrations.mqtt", integrations.mqtt.state_rate_hz, "state_rate_hz", "Hz", 0.1, 10.0,
             "State documents per second."),
    XR_S_BOOL("integrations.mqtt", integrations.mqtt.commands_enabled, "commands_enabled",
              "Offer off/auto and limp home to Home Assistant (needs username and password)."),
    XR_S_BOOL("integrations.mqtt", integrations.mqtt.tls, "tls", "Connect with TLS."),
    XR_S_STR("integrations.mqtt", integrations.mqtt.ca_file, "ca_file", "",
             "CA certificate file for TLS; empty = the system trust store."),
    // [integrations.victron]
    XR_S_BOOL("integrations.victron", integrations.victron.enabled, "enabled",
              "Read the battery's charge limits from a Victron GX (Venus OS MQTT)."),
    XR_S_STR("integrations.victron", integrations.victron.host, "host", "", "GX device host."),
    XR_S_INT("integrations.victron", integrations.victron.port, "port", "", 1, 65535, false, "GX MQTT port."),
    XR_S_STR("integrations.victron", integrations.victron.portal_id, "portal_id", "",
             "VRM portal id of the GX (Settings > VRM online portal)."),
    XR_S_INT("integrations.victron", integrations.victron.battery_instance, "battery_instance", "", 0, 65535,
             false, "Device instance of the battery service (512 for most BMS on CAN)."),
    // [integrations.weather]
    XR_S_BOOL("integrations.weather", integrations.weather.enabled, "enabled",
              "Read a daily solar forecast (Open-Meteo format) that turns weather mode on and off."),
    XR_S_STR("integrations.weather", integrations.weather.url, "url", "",
             "Open-Meteo-compatible daily forecast endpoint (http://host[:port]/path)."),
    XR_S_FLT("integrations.weather", integrations.weather.latitude, "latitude", "deg", -90.0, 90.0,
             "Where the boat is, for the forecast (north positive)."),
    XR_S_FLT("integrations.weather", integrations.weather.longitude, "longitude", "deg", -180.0, 180.0,
             "Where the boat is, for the forecast (east positive)."),
    XR_S_INT("integrations.weather", integrations.weather.refresh_min, "refresh_min", "min", 1, 1440, false,
             "Minutes between forecasts."),
    // [notify] (docs/integrations.md "Alarms that reach the owner")
    XR_S_STR("notify", integrations.notify.url, "url", "",
             "Where each incident's start and end is POSTed (http://host[:port]/path or https://...; empty = "
             "no push)."),
    XR_S_STR(
        "notify", integrations.notify.header, "header", "",
        "One extra request header, \"Name: value\" (e.g. \"Authorization: Bearer <token>\"); empty = none."),
    XR_S_STR("notify", integrations.notify.format, "format", "json,text",
             "json: one JSON document; text: a plain-text body with a Title header (ntfy and similar)."),
    XR_S_STR("notify", integrations.notify.name, "name", "",
             "The regulator's name in each message; empty = the board's host name."),
    XR_S_INT("notify", integrations.notify.timeout_s, "timeout_s", "s", 2, 120, false,
             "Seconds one delivery may take (connect, send, answer) before it is retried."),
    // [pairing] (docs/security.md "Pairing without a terminal")
    XR_S_INT("pairing", pairing.button_line, "button_line", "", -1, 1023, false,
             "GPIO line of a push button to GND (internal pull-up) on [hardware] gpio_chip: a press opens "
             "pairing without a code for 2 minutes, for one phone (-1 = no button)."),
};

#undef XR_S_STR
#undef XR_S_INT
#undef XR_S_FLT
#undef XR_S_BOOL

constexpr std::array<std::string_view, 12> kTables{"hardware",
                                                   "hardware.frontend",
                                                   "runtime",
                                                   "web",
                                                   "store",
                                                   "log",
                                                   "integrations.signalk",
                                                   "integrations.mqtt",
                                                   "integrations.victron",
                                                   "integrations.weather",
                                                   "notify",
                                                   "pairing"};

std::string rangeText(const SettingSpec& spec) {
  std::string r = "allowed " + formatNumber(spec.min) + " to " + formatNumber(spec.max);
  if (!spec.unit.empty()) r += " " + std::string(spec.unit);
  return r;
}

}  // namespace

std::span<const SettingSpec> settingsSchema() { return kSchema; }
std::span<const std::string_view> settingsTables() { return kTables; }

const SettingSpec* findSetting(std::string_view table, std::string_view key) {
  for (const auto& s : kSchema)
    if (s.table == table && s.key == key) return &s;
  return nullptr;
}

std::string checkSettingValue(const SettingSpec& spec, const SettingValue& v) {
  switch (spec.kind) {
    case SettingKind::Int: {
      const auto i = std::get<std::int64_t>(v);
      if (i < spec.min || i > spec.max) return std::to_string(i) + " is out of range: " + rangeText(spec);
      return {};
    }
    case SettingKind::Float: {
      const double d = std::get<double>(v);
      if (!std::isfinite(d) || d < spec.min || d > spec.max)
        return formatNumber(d) + " is out of range: " + rangeText(spec);
      return {};
    }
    case SettingKind::IntList: {
      const auto& l = std::get<std::vector<std::int64_t>>(v);
      if (l.empty()) return "must not be empty";
      for (auto i : l)
        if (i < spec.min || i > spec.max)
          return "element " + std::to_string(i) + " is out of range: " + rangeText(spec);
      return {};
    }
    case SettingKind::String: {
      if (spec.choices.empty()) return {};
      const auto& s = std::get<std::string>(v);
      std::string_view rest = spec.choices;
      while (!rest.empty()) {
        const auto comma = rest.find(',');
        if (rest.substr(0, comma) == s) return {};
        if (comma == std::string_view::npos) break;
        rest.remove_prefix(comma + 1);
      }
      return "\"" + s + "\" is not one of: " + std::string(spec.choices);
    }
    case SettingKind::Bool:
      return {};
  }
  return {};
}

}  // namespace xr

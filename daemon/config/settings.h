#pragma once
// Non-parameter settings of xregulator.toml: [hardware], [runtime], [web],
// [store], [log], [integrations.*]. Parameters (the catalogue) live in params/params.h.
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "params/params.h"

namespace xr {

// Analog front end of the upstream board (ADS1115 channels). The drivers and
// the simulator both scale through drivers/frontend with these values.
struct AnalogFrontEndSettings {
  double divider_r_top_ohm = 1.0e6;  // CH0 battery voltage divider
  double divider_r_bottom_ohm = 75.0e3;
  double hall_zero_v = 2.5;                // CH1 Hall output at 0 A
  double hall_sensitivity_v_per_a = 0.02;  // 20 mV/A (a 100 A-class sensor)
  bool hall_invert = false;
  double rpm_per_volt = 1000.0;     // CH2 LM2907 output scaling (engine RPM per V at the crank)
  double pulley_ratio = 1.0;        // alternator/crank ratio folded into rpm_per_volt if 1
  double rpm_low_floor = 50.0;      // below this the reading is 0 RPM (LM2907 offset)
  double thermistor_beta = 3950.0;  // CH3
  double thermistor_r0_ohm = 10000.0;
  double thermistor_t0_c = 25.0;
  double thermistor_series_r_ohm = 10000.0;
  double thermistor_supply_v = 3.3;
};

struct HardwareSettings {
  std::string i2c_bus = "/dev/i2c-1";
  std::uint16_t ina228_address = 0x40;
  std::uint16_t ads1115_address = 0x48;
  double shunt_resistance_ohm = 0.0005;  // 500 µΩ: 100 A at 50 mV
  double shunt_max_current_a = 200.0;    // sets CURRENT_LSB = max / 2^19
  AnalogFrontEndSettings frontend;
  std::vector<int> ads_channel_sequence{1, 0, 1, 2, 1, 3};  // favours CH1 (alternator current)
  int ads_alert_rdy_line = 27;  // GPIO line of ALERT/RDY (-1: not wired, single-shot pacing)
  std::string pwm_sysfs_root = "/sys/class/pwm";
  int pwm_chip = 0;
  int pwm_channel = 0;
  double pwm_frequency_hz = 400.0;
  bool pwm_inverted = false;
  std::string gpio_chip = "gpiochip0";
  int field_enable_line = 4;
  bool field_enable_active_high = true;
  int buzzer_line = 21;
  int bms_line = -1;            // -1: not wired
  bool bms_active_low = false;  // level that means "charge disabled"
  int ignition_line = -1;       // -1: not wired (treated as on)
  bool ignition_active_low = false;
  std::string watchdog_device = "/dev/watchdog";
  int watchdog_timeout_s = 16;
  std::string w1_root = "/sys/bus/w1/devices";
  std::string onewire_sensor_id;    // "28-..." or empty for the first found
  std::string battery_temp_sensor;  // battery DS18B20 "28-..."; empty = none (docs/batteries.md)
  std::string vedirect_port;        // e.g. /dev/ttyUSB0, empty = none
};

struct RuntimeSettings {
  int control_period_us = 2500;  // 400 Hz tick
  int rt_priority = 80;          // SCHED_FIFO priority
  int cpu = -1;                  // pin the control thread to this CPU (-1 = no pinning)
};

struct WebSettings {
  std::string listen = "0.0.0.0";  // reads on the LAN; writes need pairing (docs/security.md)
  int port = 8080;
  std::string token;  // empty: generated at first start, stored with the state
  double telemetry_rate_hz = 10.0;
  bool reads_require_token = false;
  int max_connections = 64;
  std::string www_root;  // dashboard assets; empty = built-in default path
};

// [pairing] (docs/security.md "Pairing without a terminal").
struct PairingSettings {
  int button_line = -1;  // GPIO line of a push button to GND that opens pairing; -1: none
};

struct StoreSettings {
  std::string path = "/var/lib/xregulator/xregulator.db";
  int checkpoint_interval_s = 300;
};

struct LogSettings {
  std::string level = "info";  // trace, debug, info, warn, error, critical
};

// [integrations.*] (docs/integrations.md): the boat's network. Each is off by default
// and runs on the integrations thread, never the control thread.
struct SignalKSettings {
  bool enabled = false;
  std::string url = "ws://localhost:3000/signalk/v1/stream?subscribe=none";
  double rate_hz = 1.0;                // deltas per second (state changes go at once)
  std::string alternator_id = "main";  // electrical.alternators.<id>
  std::string battery_id = "house";    // electrical.batteries.<id>
};

struct MqttSettings {
  bool enabled = false;
  std::string host = "localhost";
  int port = 1883;
  std::string username;
  std::string password;
  std::string discovery_prefix = "homeassistant";
  std::string node_id = "main";  // xregulator_<node_id> in the topics
  double state_rate_hz = 1.0;
  bool commands_enabled = false;  // needs username and password too
  bool tls = false;
  std::string ca_file;  // TLS trust anchor; empty = the system store
};

struct VictronSettings {
  bool enabled = false;
  std::string host = "venus.local";
  int port = 1883;
  std::string portal_id;
  int battery_instance = 512;
  // Staleness is the BmsStaleS parameter, shared with a BMS on CAN.
};

// [integrations.weather] (docs/integrations.md "Weather"): an Open-Meteo
// daily forecast that turns weather mode on and off.
struct WeatherSettings {
  bool enabled = false;
  std::string url = "http://api.open-meteo.com/v1/forecast";  // http:// only
  double latitude = 0.0;                                      // degrees, north positive
  double longitude = 0.0;                                     // degrees, east positive
  int refresh_min = 60;
};

// [notify] (docs/integrations.md "Alarms that reach the owner"): one HTTP
// POST per incident start and end, to a push service or the owner's own
// receiver. Off while url is empty.
struct NotifySettings {
  std::string url;              // http://host[:port]/path or https://...; empty = off
  std::string header;           // one extra header, "Name: value" (a token); empty = none
  std::string format = "json";  // json | text (the body push services such as ntfy show as it is)
  std::string name;             // the regulator's name in the message; empty = the board's host name
  int timeout_s = 10;           // one attempt: connect, send, answer
};

struct IntegrationsSettings {
  SignalKSettings signalk;
  MqttSettings mqtt;
  VictronSettings victron;
  WeatherSettings weather;
  NotifySettings notify;  // the [notify] table
};

// [can] (docs/integrations.md "CAN"): the two buses and what is spoken on
// them. The BMS-following parameters (BmsStaleS, ...) sit in the same table.
struct CanSettings {
  std::string bms_interface;             // SocketCAN interface of the BMS bus (500 kbit/s), empty = none
  std::string bms_protocol = "victron";  // victron | pylontech | rec
  std::string n2k_interface;             // NMEA 2000 bus (250 kbit/s), empty = none
  int n2k_preferred_address = 35;        // first address claimed (60928); moves on a conflict
  std::string RpmSource = "tach";        // tach (ADS1115 CH2) | n2k (PGN 127488 engine speed)
};

struct Settings {
  HardwareSettings hardware;
  CanSettings can;
  RuntimeSettings runtime;
  WebSettings web;
  StoreSettings store;
  LogSettings log;
  IntegrationsSettings integrations;
  PairingSettings pairing;
};

// The whole configuration: settings plus the parameter set.
struct Config {
  Settings settings;
  Params params;  // defaults, then the battery profile, then the file
  // Where the values came from (--print-config, GET /api/params):
  // the parameters written in the file, and those the profile filled.
  std::set<std::string, std::less<>> fileParamNames;
  std::set<std::string, std::less<>> profileParamNames;
  // File values read otherwise than written, each in one sentence (the start
  // log and --check-config print them as warnings).
  std::vector<std::string> notices;
};

}  // namespace xr

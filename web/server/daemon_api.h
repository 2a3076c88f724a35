#pragma once
// DaemonApi: everything the web server needs from the daemon, and nothing else.
//
// Implemented by daemon/runtime (engineer "runtime"); a fake lives in
// tests/web/fake_daemon_api.h. The web server calls these methods from its
// Asio threads only (never from the control thread). Every method must be
// NON-BLOCKING for the control thread: read the latest telemetry from the
// seqlock/triple buffer, push commands and parameter sets into the SPSC
// queues the control thread drains between ticks, and query the store from
// the calling (Asio) thread. Methods may be called concurrently from the
// server's threads, so implementations must be thread-safe among themselves.
//
// The server does all JSON formatting; the daemon hands out plain structs.
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "control/telemetry.h"
#include "core/charge_summaries.h"
#include "core/commands.h"
#include "core/events.h"
#include "core/time.h"
#include "core/trend_rows.h"
#include "params/params.h"

namespace xr::web {

// Control-loop timing measured by the runtime (docs/architecture.md "Threads").
struct LoopStats {
  std::uint64_t ticks = 0;     // ticks since start
  std::uint64_t overruns = 0;  // deadlines missed entirely (skipped)
  // Of them, those the daemon caused: the tick used a whole period of CPU
  // time. The rest are late wake-ups or preemption (a loaded machine).
  std::uint64_t overruns_own = 0;
  double target_period_us = 0.0;  // [runtime] control_period_us
  double period_mean_us = 0.0;    // measured tick-to-tick period
  double period_p99_us = 0.0;
  double period_max_us = 0.0;
  double exec_mean_us = 0.0;  // time spent inside one tick (read, step, write)
  double exec_p99_us = 0.0;
  double exec_max_us = 0.0;
  double tick_cpu_p99_us = 0.0;  // the control thread's CPU time per tick
  double tick_cpu_max_us = 0.0;
  std::uint64_t sensor_errors = 0;  // failed I2C reads since start
};

// The simulator plant's truth (CSV columns sim_*, docs/operations.md). Absent on hardware.
struct SimTruth {
  double battery_v = 0.0;
  double alt_a = 0.0;
  double alt_temp_f = 0.0;
  double soc_pct = 0.0;
  bool bms_connected = true;
  bool field_on = false;
};

// One extra number the runtime wants on the dashboard that has no home in the
// core telemetry structs yet, e.g. {"tuning", "score", 0.82},
// {"tuning", "cvScore", ...}, {"system_id", "gain", ...}. Serialised in
// /api/status as status[section][name] = value.
struct ExtraValue {
  std::string section;
  std::string name;
  double value = 0.0;
};

// One status snapshot: the latest published tick plus what surrounds it.
struct StatusSnapshot {
  std::uint64_t seq = 0;     // increments with every published telemetry; 0 = none yet
  TimeNs start = 0;          // t_s = telemetry.now - start (simulated time in sim)
  double wall_time_s = 0.0;  // Unix epoch seconds when this tick was published
  Telemetry telemetry;
  LoopStats loop;
  std::optional<SimTruth> sim;  // present in simulation
  std::vector<ExtraValue> extras;
  // For the owner model (daemon/owner): whether a battery type is chosen,
  // and the limits that hold until it is.
  bool setUp = true;
  std::string setupLimits;
};

// Hardware probe result (xregulatord --probe and the start-up probe).
struct ProbeResult {
  std::string device;  // "INA228 @0x40 on /dev/i2c-1"
  bool ok = false;
  std::string detail;  // "manufacturer 0x5449 device 0x228" or the error
};

// Versions and identity for the System page, e.g. {"xregulatord", "0.1.0"},
// {"git", "792c09a"}, {"boost", "1.81"}, {"mode", "sim"}.
using VersionMap = std::map<std::string, std::string>;

// One parameter change requested by PATCH /api/params. Scalars: index = -1.
// Tables: the server expands a JSON array into one change per element
// (index 0..RPM_TABLE_SIZE-1). `spec` points into catalogue().
struct ParamChange {
  const ParamSpec* spec = nullptr;
  int index = -1;
  double value = 0.0;
  // JSON null in a PATCH: forget the dashboard's value of this parameter, so
  // the layer below (file, profile or default) applies again.
  bool drop = false;
};

// A per-field rejection: name = parameter name, message = why.
struct FieldError {
  std::string name;
  std::string message;
};

// Result of patchParams: empty errors = every change applied (and persisted as
// overrides); otherwise NOTHING was applied. values: the whole set as the
// daemon checked it (a dry run answers it; empty when a value was malformed).
struct PatchResult {
  std::vector<FieldError> errors;
  std::optional<Params> values;
};

// How a PATCH is taken (docs/dashboard.md "Set-up"). dryRun: check the whole
// set and answer it, applying and storing nothing. bankV: the set-up's bank
// choice (12, 24 or 48 V; 0 = none), which the daemon turns into values (the
// chemistry's cell count, or a custom set's voltages moved to that bank):
// the dashboard knows no rule of the catalogue or the profiles.
struct PatchOptions {
  bool dryRun = false;
  int bankV = 0;
};

// A Victron GX's DVCC limits (POST /api/dvcc, core/dvcc_limits.h): NaN = the
// GX did not send this one. `source` names the writer, for the journal;
// `refusal` non-empty: the body itself was bad (the daemon refuses and logs).
struct DvccRequest {
  double chargeVoltageV = std::numeric_limits<double>::quiet_NaN();
  double chargeCurrentA = std::numeric_limits<double>::quiet_NaN();
  std::string source;
  std::string refusal;
};

// Result of command(): accepted = queued for the control thread.
struct CommandResult {
  bool accepted = false;
  std::string message;  // why it was refused, or a short confirmation
};

// One stored event (from the store, newest first).
struct EventRecord {
  std::int64_t id = 0;       // store row id, increasing; `before` pages on it
  double wall_time_s = 0.0;  // Unix epoch seconds
  Event event;               // core/events.h
  std::string text;          // describe(event), formatted off the RT thread
};

struct EventQuery {
  std::size_t limit = 100;             // server clamps to [1, 1000]
  std::optional<std::int64_t> before;  // only ids < before
};

// History: numeric telemetry columns (docs/operations.md "Telemetry CSV columns") averaged over
// buckets of `step_s` seconds. Times are Unix epoch seconds.
struct HistoryQuery {
  std::vector<std::string> series;  // e.g. {"battery_v", "alt_a"}; validated by the daemon
  double from_s = 0.0;
  double to_s = 0.0;
  double step_s = 10.0;
};

struct HistoryResult {
  std::string error;      // non-empty: 400 with this message (unknown series...)
  std::vector<double> t;  // bucket start times
  std::vector<std::pair<std::string, std::vector<double>>> series;  // same length as t; NaN = no data
};

// One integration with the boat's network (signalk, mqtt,
// victron) for /api/system and /metrics.
struct IntegrationState {
  std::string name;
  bool enabled = false;
  bool connected = false;
  std::string last_error;
  std::uint64_t messages_sent = 0, messages_received = 0, messages_dropped = 0, values_refused = 0,
                outages = 0;
  std::map<std::string, double> values;      // what it reads (the Victron limits); NaN = none
  std::map<std::string, std::string> texts;  // what it reads that is a word (weather: position_source)
};

// The CAN buses (docs/integrations.md) for /api/system. Unknown numbers are NaN (null
// in JSON), never invented.
struct CanBmsState {
  std::string protocol;       // victron | pylontech | rec; empty when off
  std::string state = "off";  // off | bus_error | silent | talking
  bool follow = true;  // false: monitor only (BmsLimitsEnabled = 0), the limits are shown, not followed
  double cvl_v = std::numeric_limits<double>::quiet_NaN();
  double ccl_a = std::numeric_limits<double>::quiet_NaN();
  double soc_pct = std::numeric_limits<double>::quiet_NaN();
  double cell_max_v = std::numeric_limits<double>::quiet_NaN();  // rec only
  double age_s = std::numeric_limits<double>::quiet_NaN();       // since the last CVL/CCL (0x351)
  std::uint64_t frames = 0, bad_frames = 0, error_frames = 0, open_failures = 0;
};
struct CanN2kState {
  std::string state = "off";  // off | bus_error | claimed | no_address
  bool claimed = false;
  int address = -1;  // -1 = none
  std::uint64_t tx_frames = 0, rx_frames = 0, error_frames = 0, open_failures = 0;
};
struct CanState {
  CanBmsState bms;
  CanN2kState n2k;
};

// The set-up page's hardware choices (GET/PUT /api/setup/hardware,
// docs/configuration.md "Set-up"): the battery's 1-Wire probe and the BMS's
// CAN interface. Each is what the file says, what the set-up page chose
// (nullopt: nothing; "" = none) and what runs now; a choice runs from the
// next start.
template <class T>
struct HardwareChoice {
  T file{};
  std::optional<T> chosen;
  T running{};
};
struct HardwareSetup {
  bool savable = false;  // a state database keeps the choices
  HardwareChoice<std::string> batteryTempSensor;
  HardwareChoice<std::string> bmsInterface;
  HardwareChoice<double> pulleyRatio;      // alternator turns per engine turn
  std::string alternatorSensor;            // the probe the alternator's temperature is read from
  std::vector<std::string> probes;         // 1-Wire temperature probes present now
  std::vector<std::string> canInterfaces;  // CAN interfaces present now
  bool victronBms = false;                 // the GX gives the BMS limits ([integrations.victron])
};
// One field of PUT /api/setup/hardware: absent (not touched), a value, or
// null (back to the file's).
template <class T>
struct ChoiceEdit {
  bool touched = false;
  std::optional<T> value;
};
struct HardwareChoiceEdit {
  ChoiceEdit<std::string> batteryTempSensor;
  ChoiceEdit<std::string> bmsInterface;
  ChoiceEdit<double> pulleyRatio;
};

// Health for /healthz: ok = the control loop ticks and the outputs are driven.
struct Health {
  bool ok = false;
  std::string detail;
};

class DaemonApi {
 public:
  virtual ~DaemonApi() = default;

  // Latest status. Returns false (and leaves `out` alone) before the first tick.
  // Called by the server's broadcast timer at the WebSocket rate and by
  // GET /api/status; must be a cheap copy out of the lock-free hand-off.
  virtual bool latestStatus(StatusSnapshot& out) = 0;

  // Parameters: the set in force now, and the set read from the config file
  // (before runtime overrides). Defaults are Params{} (catalogue defaults).
  virtual Params currentParams() = 0;
  virtual Params fileParams() = 0;
  // Where each parameter's value comes from, by name: "default", "profile",
  // "file" or "dashboard" (docs/batteries.md). Empty: the server infers it from
  // currentParams() and fileParams() (no profile known).
  virtual std::map<std::string, std::string> paramSources() { return {}; }
  // The names a battery profile sets when nothing above it does; the set-up
  // page drops the dashboard's values of these when a chemistry is chosen.
  virtual std::set<std::string> profileOwned() { return {}; }
  // The values the battery profile chosen now gives its names (the rest at
  // their catalogue defaults): what "Default" means on the Settings page.
  virtual Params effectiveDefaults() { return Params{}; }
  // Whether a battery type is chosen; until then, the limits in force in
  // words (docs/configuration.md "Not set up").
  struct SetupState {
    bool setUp = true;
    std::string limits;
  };
  virtual SetupState setupState() { return {}; }

  // Apply a set of changes atomically: validate them TOGETHER against the
  // current set (cross-field rules), then hand the whole new Params to the
  // control thread between ticks and persist the overrides; or reject them
  // all. The server has only parsed the body (names, JSON types): every
  // check of the values, ranges included, is the daemon's, once.
  // source: who asked (a paired device's name, "the installer token"); the
  // daemon records an applied change as an event naming each value's old and
  // new value and the source (docs/dashboard.md).
  virtual PatchResult patchParams(const std::vector<ParamChange>& changes, const std::string& source,
                                  const PatchOptions& opts = {}) = 0;

  // A security action (pairing, revocation, a pairing lock-out): an event in
  // the list and a journal line, naming the device (docs/security.md).
  virtual void securityEvent(const std::string& text) { (void)text; }

  // Queue an operator command for the control thread (core/commands.h).
  virtual CommandResult command(const Command& cmd) = 0;
  // Hand a GX's DVCC limits to the control thread beside the BMS's
  // (docs/integrations.md "Victron GX"); refused with the reason when a value
  // is out of range, or when this daemon takes none.
  virtual CommandResult dvccLimits(const DvccRequest& /*req*/) {
    return {false, "this daemon takes no DVCC limits"};
  }

  virtual std::vector<EventRecord> events(const EventQuery& q) = 0;
  virtual HistoryResult history(const HistoryQuery& q) = 0;
  // The History page's summaries, newest first (docs/dashboard.md
  // "History"); empty without a state database.
  virtual std::vector<DaySummary> historyDays(std::size_t /*n*/) { return {}; }
  virtual std::vector<ChargeSummary> historyCharges(std::size_t /*n*/) { return {}; }
  // The charges that started on a local day "YYYY-MM-DD", oldest first;
  // nullopt when there is no such day (2026-02-30).
  virtual std::optional<std::vector<ChargeSummary>> historyChargesOn(const std::string& /*day*/) {
    return std::vector<ChargeSummary>{};
  }
  // Trend rows starting in [fromS, toS], oldest first (core/trend_rows.h).
  virtual std::vector<TrendRow> historyTrends(std::int64_t /*fromS*/, std::int64_t /*toS*/, bool /*daily*/) {
    return {};
  }

  virtual std::vector<ProbeResult> probeResults() = 0;
  virtual VersionMap versions() = 0;
  virtual Health health() = 0;
  // The integrations' state; none when the daemon runs without them.
  virtual std::vector<IntegrationState> integrations() { return {}; }
  // The CAN buses; both "off" when the daemon has none.
  virtual CanState can() { return {}; }

  // The set-up page's hardware choices; saving checks them as the file's
  // settings are checked and keeps them durably, or changes nothing and
  // says why (FieldError.name: the setting's dotted key).
  virtual HardwareSetup hardwareSetup() { return {}; }
  virtual std::vector<FieldError> saveHardwareChoices(const HardwareChoiceEdit& /*edit*/,
                                                      const std::string& /*source*/) {
    return {{"setup", "this daemon keeps no hardware choices"}};
  }
};

}  // namespace xr::web

#pragma once
// FakeDaemonApi: a thread-safe stand-in for the runtime's DaemonApi, used by
// the API tests, the fuzz target and the browser-test server. Telemetry is a
// deterministic function of the sequence number; publish() advances it.
#include <cmath>
#include <mutex>
#include <string>
#include <vector>

#include "core/commands.h"
#include "web/server/daemon_api.h"

namespace xr::web::test {

class FakeDaemonApi : public DaemonApi {
 public:
  // Where the published SoC comes from (a test sets Unknown or OcvEstimate).
  SocSource socSource = SocSource::Counted;
  // The owner model's inputs beside the plain columns (docs/dashboard.md "Owner model").
  CommandCaps caps;
  BmsState bmsState = BmsState::OFF;
  double bmsSocPct = kBmsNoValue;
  bool setUp = true;
  FakeDaemonApi() {
    for (int i = 1; i <= 250; ++i) {
      EventRecord r;
      r.id = i;
      r.wall_time_s = 1.7e9 + i;
      r.event.t = static_cast<TimeNs>(i) * 1'000'000'000;
      r.event.code = i % 2 ? EventCode::StageChanged : EventCode::ProtectionTrip;
      r.event.level = i % 2 ? EventLevel::Info : EventLevel::Warning;
      r.event.reason = i % 2 ? Reason::NONE : Reason::REASON_TEMP_WARNING;
      r.text = "event " + std::to_string(i);
      events_.push_back(r);
    }
  }

  // Publishes the next tick; values are a function of seq.
  void publish() {
    std::lock_guard lock(m_);
    ++seq_;
    const double k = static_cast<double>(seq_);
    StatusSnapshot& s = snap_;
    s.seq = seq_;
    s.start = 0;
    s.wall_time_s = 1.7e9 + k * 0.1;
    auto& t = s.telemetry;
    t.now = static_cast<TimeNs>(seq_) * 100'000'000;  // 0.1 s per tick
    t.mode = FieldControlMode::MODE_NORMAL_AUTO_PID;
    t.stage = ChargeStage::BULK;
    t.reason = Reason::NONE;
    t.battery_v = 13.2 + 0.4 * std::sin(k / 10.0);
    t.ibv_v = t.battery_v + 0.01;
    t.bcur_a = 40.0 + 10.0 * std::sin(k / 7.0);
    t.alt_a = 55.0 + 15.0 * std::sin(k / 9.0);
    t.rpm = 1800.0;
    t.temp_f = 150.0 + k * 0.01;
    t.duty_pct = 42.5;
    t.field_enable = true;
    t.setpoint_a = 60.0;
    t.target_a = 60.0;
    t.target_v = 14.5;
    t.soc_pct = 55.0 + k * 0.001;
    t.charged_wh_lifetime = 1234.5;
    t.battery.SOC_percent = t.soc_pct;
    t.battery.socSource = socSource;
    t.battery.socKnown = socSource == SocSource::Counted;
    t.battery.ChargeCycles = 12.3;
    t.battery.timeToFullChargeMin = 95.0;
    t.protection.lastTripReason = Reason::REASON_TEMP_WARNING;
    t.control.sysMode = SysMode::SYS_MODE_AUTO;
    t.caps = caps;
    t.bms_state = bmsState;
    t.bms_soc_pct = bmsSocPct;
    s.setUp = setUp;
    s.setupLimits = setUp ? "" : "at most 14.0 V, float 13.4 V";
    s.loop.ticks = seq_ * 40;
    s.loop.target_period_us = 2500;
    s.loop.period_p99_us = 2510;
    s.loop.overruns = 5;
    s.loop.overruns_own = 2;
    s.loop.tick_cpu_p99_us = 41.5;
    s.loop.tick_cpu_max_us = 310.0;
    s.sim = SimTruth{t.battery_v, t.alt_a, t.temp_f, t.soc_pct, true, true};
    s.extras = {{"tuning", "score", 0.8}, {"tuning", "cvScore", 0.6}};
  }

  bool latestStatus(StatusSnapshot& out) override {
    std::lock_guard lock(m_);
    if (seq_ == 0) return false;
    out = snap_;
    return true;
  }
  Params currentParams() override {
    std::lock_guard lock(m_);
    return current_;
  }
  Params fileParams() override {
    std::lock_guard lock(m_);
    return file_;
  }
  // Cross-field rule (like the real validation): FloatVoltage <= BulkVoltage.
  // A dry run answers the set and keeps nothing.
  PatchResult patchParams(const std::vector<ParamChange>& changes, const std::string& source,
                          const PatchOptions& opts = {}) override {
    std::lock_guard lock(m_);
    ++patchCalls_;
    lastPatchSource_ = source;
    lastPatchOptions_ = opts;
    Params next = current_;
    for (const auto& c : changes)
      c.spec->set(next, c.index < 0 ? 0 : static_cast<std::size_t>(c.index),
                  c.drop ? c.spec->get(file_, 0) : c.value);  // drop: the file's value again
    PatchResult r;
    if (next.FloatVoltage > next.BulkVoltage)
      r.errors.push_back({"FloatVoltage", "must not exceed BulkVoltage"});
    r.values = next;
    if (r.errors.empty() && !opts.dryRun) current_ = next;
    return r;
  }
  void securityEvent(const std::string& text) override {
    std::lock_guard lock(m_);
    securityEvents_.push_back(text);
  }
  std::vector<std::string> securityEvents() {
    std::lock_guard lock(m_);
    return securityEvents_;
  }
  CommandResult command(const Command& cmd) override {
    std::lock_guard lock(m_);
    commands_.push_back(cmd);
    if (refuseCommands_) return {false, "not legal now"};
    return {true, "queued"};
  }
  std::vector<EventRecord> events(const EventQuery& q) override {
    std::lock_guard lock(m_);
    std::vector<EventRecord> out;
    for (auto it = events_.rbegin(); it != events_.rend() && out.size() < q.limit; ++it)
      if (!q.before || it->id < *q.before) out.push_back(*it);
    return out;
  }
  // One day and one open charge, with small and large decimals in them.
  std::vector<DaySummary> historyDays(std::size_t) override {
    DaySummary d;
    d.day = "2026-07-01";
    d.altAh = 123.456789;
    d.altWh = 1728.39512;
    d.bulkS = 4321.5;
    d.peakAltTempC = 88.04;
    d.minSocPct = 0.0000123;
    return {d};
  }
  std::vector<ChargeSummary> historyCharges(std::size_t) override {
    ChargeSummary c;
    c.id = 7;
    c.startMs = 1'782'900'000'123;
    c.endMs = c.startMs + 5'400'000;
    c.altAh = 0.000042;
    return {c};
  }
  // Two hours of trend rows from fromS (the battery temperature not known),
  // and the range asked for (web_trends_test.cpp).
  std::vector<TrendRow> historyTrends(std::int64_t fromS, std::int64_t toS, bool daily) override {
    std::lock_guard lock(m_);
    lastTrends_ = {fromS, toS, daily};
    std::vector<TrendRow> out;
    for (int i = 0; i < 2; ++i) {
      TrendRow r;
      r.startS = r.dayS = fromS + i * 3600;
      r.samples = 3600;
      r.stat[0] = {12.4567, 13.1234567, 14.4};
      r.stat[1] = {-20.0, 5.55555, 80.0};
      out.push_back(r);
    }
    return out;
  }
  std::optional<std::vector<ChargeSummary>> historyChargesOn(const std::string& day) override {
    if (day == "2026-02-30") return std::nullopt;
    return historyCharges(1);
  }
  struct TrendAsk {
    std::int64_t fromS = 0, toS = 0;
    bool daily = false;
  };
  TrendAsk lastTrends() {
    std::lock_guard lock(m_);
    return lastTrends_;
  }
  HistoryResult history(const HistoryQuery& q) override {
    HistoryResult r;
    for (const auto& s : q.series)
      if (s != "battery_v" && s != "ibv_v" && s != "alt_a" && s != "bcur_a" && s != "temp_f" &&
          s != "soc_pct" && s != "rpm" && s != "duty_pct") {
        r.error = "unknown series '" + s + "'";
        return r;
      }
    for (double t = q.from_s; t < q.to_s; t += q.step_s) r.t.push_back(t);
    // The newest bucket is still open and empty, as in the store; the
    // temperature and RPM steady with a little noise, as when cruising.
    const auto sample = [&q](const std::string& s, double t) {
      if (t + q.step_s >= q.to_s) return std::nan("");
      if (s == "battery_v" || s == "ibv_v") return 13.0 + 0.5 * std::sin(t / 300.0);
      if (s == "temp_f") return 180.0 + 0.4 * std::sin(t / 20.0);
      if (s == "rpm") return 1800.0 + 5.0 * std::sin(t / 7.0);
      return 50.0 + 20.0 * std::sin(t / 200.0);
    };
    for (const auto& s : q.series) {
      std::vector<double> v;
      for (double t : r.t) v.push_back(sample(s, t));
      r.series.emplace_back(s, std::move(v));
    }
    std::lock_guard lock(m_);
    lastHistory_ = q;
    return r;
  }
  std::vector<ProbeResult> probeResults() override {
    return {{"INA228 @0x40 on sim", true, "manufacturer 0x5449 device 0x228"},
            {"ADS1115 @0x48 on sim", false, "no ACK"}};
  }
  VersionMap versions() override { return {{"xregulatord", "test"}, {"mode", "fake"}}; }
  CanState can() override {
    std::lock_guard lock(m_);
    return can_;
  }
  void setCan(const CanState& c) {
    std::lock_guard lock(m_);
    can_ = c;
  }
  Health health() override {
    std::lock_guard lock(m_);
    return healthy_ ? Health{true, "control loop ticking"} : Health{false, "no tick for 5 s"};
  }

  // Test controls.
  void setHealthy(bool h) {
    std::lock_guard lock(m_);
    healthy_ = h;
  }
  void setRefuseCommands(bool r) {
    std::lock_guard lock(m_);
    refuseCommands_ = r;
  }
  std::vector<Command> commands() {
    std::lock_guard lock(m_);
    return commands_;
  }
  int patchCalls() {
    std::lock_guard lock(m_);
    return patchCalls_;
  }
  std::string lastPatchSource() {
    std::lock_guard lock(m_);
    return lastPatchSource_;
  }
  PatchOptions lastPatchOptions() {
    std::lock_guard lock(m_);
    return lastPatchOptions_;
  }
  HistoryQuery lastHistory() {
    std::lock_guard lock(m_);
    return lastHistory_;
  }

 private:
  std::mutex m_;
  std::uint64_t seq_ = 0;
  StatusSnapshot snap_;
  Params current_{};
  Params file_{};
  std::vector<Command> commands_;
  std::vector<EventRecord> events_;
  HistoryQuery lastHistory_;
  TrendAsk lastTrends_;
  int patchCalls_ = 0;
  std::string lastPatchSource_;
  PatchOptions lastPatchOptions_;
  std::vector<std::string> securityEvents_;
  bool healthy_ = true;
  CanState can_;
  bool refuseCommands_ = false;
};

}  // namespace xr::web::test

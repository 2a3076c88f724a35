#include "app/web_api.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

#include "app/daemon_notices.h"
#include "app/effective_params.h"
#include "app/param_change_text.h"
#include "config/config.h"
#include "config/setup_pending.h"
#include "core/modes.h"
#include "core/wall_time_text.h"

namespace xr::app {

web::StatusSnapshot WebApi::toStatus(const rt::RuntimeSnapshot& s, bool sim, double periodUs) {
  web::StatusSnapshot o;
  o.seq = s.tick;
  o.start = s.start;
  o.wall_time_s = static_cast<double>(unixMsNow()) / 1000.0;
  o.telemetry = s.telemetry;
  o.loop.ticks = s.loop.ticks;
  o.loop.overruns = s.loop.overruns;
  o.loop.overruns_own = s.loop.overrunsOwn;
  o.loop.tick_cpu_p99_us = s.loop.tickCpuP99Us;
  o.loop.tick_cpu_max_us = s.loop.tickCpuMaxUs;
  o.loop.target_period_us = periodUs;
  // Absolute-deadline loop: the measured period is the target plus the
  // wake-up error, so the error quantiles are what the web shows.
  o.loop.period_mean_us = periodUs + s.loop.periodErrP50Us;
  o.loop.period_p99_us = periodUs + s.loop.periodErrP99Us;
  o.loop.period_max_us = periodUs + s.loop.periodErrMaxUs;
  o.loop.exec_mean_us = s.loop.computeP50Us + s.loop.ioP50Us;
  o.loop.exec_p99_us = s.loop.computeP99Us + s.loop.ioP99Us;
  o.loop.exec_max_us = s.loop.computeMaxUs + s.loop.ioMaxUs;
  o.loop.sensor_errors = s.health.sensorReadErrors;
  if (sim && s.sim.valid) {
    web::SimTruth t;
    t.battery_v = s.sim.sim_battery_v;
    t.alt_a = s.sim.sim_alt_a;
    t.alt_temp_f = s.sim.sim_alt_temp_f;
    t.soc_pct = s.sim.sim_soc_pct;
    t.bms_connected = s.sim.sim_bms_connected;
    t.field_on = s.sim.sim_field_on;
    o.sim = t;
  }
  auto add = [&](const char* section, const char* name, double v) { o.extras.push_back({section, name, v}); };
  add("loop", "period_error_p50_us", s.loop.periodErrP50Us);
  add("loop", "period_error_p99_us", s.loop.periodErrP99Us);
  add("loop", "period_error_max_us", s.loop.periodErrMaxUs);
  add("loop", "compute_p50_us", s.loop.computeP50Us);
  add("loop", "compute_p99_us", s.loop.computeP99Us);
  add("loop", "compute_max_us", s.loop.computeMaxUs);
  add("loop", "io_p50_us", s.loop.ioP50Us);
  add("loop", "io_p99_us", s.loop.ioP99Us);
  add("loop", "io_max_us", s.loop.ioMaxUs);
  add("loop", "ch1_sample_rate_hz", s.loop.ch1SampleRateHz);
  for (int c = 0; c < 4; ++c) {
    static const char* names[4] = {"ch0_sample_rate_hz", "ch1_rate_hz", "ch2_sample_rate_hz",
                                   "ch3_sample_rate_hz"};
    if (c != 1) add("loop", names[c], s.loop.adsChannelRateHz[static_cast<std::size_t>(c)]);
  }
  add("loop", "ina_sample_rate_hz", s.loop.inaSampleRateHz);
  add("runtime", "output_write_errors", static_cast<double>(s.health.outputWriteErrors));
  add("runtime", "watchdog_feeds", static_cast<double>(s.health.watchdogFeeds));
  add("runtime", "commands_applied", static_cast<double>(s.health.commandsApplied));
  add("runtime", "commands_rejected", static_cast<double>(s.health.commandsRejected));
  add("runtime", "events_dropped", static_cast<double>(s.health.eventsDropped));
  add("runtime", "ads_ready_edges", static_cast<double>(s.loop.adsEdges));
  add("runtime", "ads_edge_fallback", s.health.adsEdgeFallback ? 1.0 : 0.0);
  return o;
}

bool WebApi::latestStatus(web::StatusSnapshot& out) {
  const rt::RuntimeSnapshot s = ctx_.handoffs->latest();
  if (s.tick == 0) return false;
  followBankClass(*ctx_.handoffs, s.telemetry);  // the limits below are then the bank's
  out = toStatus(s, ctx_.sim, ctx_.controlPeriodUs);
  // The owner model says "Not set up" from the same state as /api/params
  // (the hand-off's copy: patchParams calls this holding patchMutex_).
  out.setUp = ctx_.handoffs->setUp.load();
  if (!out.setUp) out.setupLimits = setupPendingLimitsText(ctx_.handoffs->acceptedParams());
  return true;
}

void WebApi::recordEvent(const std::string& code, const std::string& text) {
  // On the store's clock: in --sim the simulated one, like the core's events.
  const std::int64_t nowMs = ctx_.store ? ctx_.store->clockMs() : unixMsNow();
  if (ctx_.store) {
    EventRecord e;
    e.tMs = nowMs;
    e.level = "info";
    e.code = code;
    e.reason = "NONE";
    e.message = text;
    ctx_.store->appendRecord(e);
  }
  if (ctx_.events) {
    Event e;
    e.code = EventCode::Message;
    ctx_.events->add(e, static_cast<double>(nowMs) / 1000.0, text);
  }
}

// Pairing and revocations (docs/security.md): in the event list and in the
// journal, where an owner reading `journalctl` looks for who got access.
void WebApi::securityEvent(const std::string& text) {
  spdlog::warn("security: {}", text);
  recordEvent("Security", text);
}

web::CommandResult WebApi::command(const Command& cmd) {
  web::CommandResult r;
  const std::string name(toString(cmd.type));
  const std::uint32_t id = ctx_.handoffs->submitCommandForAck(cmd);
  if (id == 0) {
    r.message = "command queue full, try again";
    return r;
  }
  // The control thread applies commands between ticks (every 2.5 ms at
  // 400 Hz) and posts the regulator's answer without waiting for anyone;
  // this HTTP thread polls for it (docs/security.md).
  const auto deadline = std::chrono::steady_clock::now() + ctx_.commandAckTimeout;
  int answer = -1;
  while ((answer = ctx_.handoffs->acks.find(id)) < 0 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  if (answer == 1) {
    r.accepted = true;
    r.message = "applied: " + name;
  } else if (answer == 0) {
    r.message = name + " refused by the regulator: " + std::string(refusalReason(cmd.type));
  } else {
    // The loop is not ticking (stopping, or a very slow simulation): the
    // command stays queued and is applied or refused when it ticks again.
    r.accepted = true;
    r.message = "queued: " + name + " (the control loop has not answered yet)";
  }
  return r;
}

namespace {

template <class Enum, int N>
Enum parseByName(std::string_view s, Enum fallback) {
  for (int i = 0; i < N; ++i)
    if (toString(static_cast<Enum>(i)) == s) return static_cast<Enum>(i);
  return fallback;
}

// A stored event back in the API's shape. Codes the core does not know
// (the daemon's own, e.g. OverrideDropped) become Message with their text.
web::EventRecord fromStored(const EventRecord& s) {
  web::EventRecord e;
  e.id = s.id;
  e.wall_time_s = static_cast<double>(s.tMs) / 1000.0;
  e.event.level = parseByName<EventLevel, 5>(s.level, EventLevel::Info);
  // Every code, up to the last (the ones after AlarmCondition came back as
  // Message before).
  e.event.code = parseByName<EventCode, kEventCodeCount>(s.code, EventCode::Message);
  e.event.reason = parseReason(s.reason).value_or(Reason::NONE);
  e.event.a = s.a;
  e.event.b = s.b;
  e.text = s.message;
  return e;
}

}  // namespace

void WebApi::logPatch(std::size_t values) {
  // One line per PATCH flooded the journal (2,000 PATCHes, 2,000 lines).
  std::lock_guard lock(logMutex_);
  if (auto line = patchLog_.onPatch(PatchLogLimiter::Clock::now(), values); !line.empty())
    spdlog::info("{}", line);
}

void WebApi::flushPatchLog(PatchLogLimiter::Clock::time_point now) {
  std::lock_guard lock(logMutex_);
  if (auto line = patchLog_.flush(now); !line.empty()) spdlog::info("{}", line);
}

std::vector<web::EventRecord> WebApi::events(const web::EventQuery& q) {
  std::vector<web::EventRecord> out;
  // The store holds every run's events (docs/security.md); the in-memory
  // ring only this run's, and serves when there is no database.
  if (ctx_.store && ctx_.store->status().persistent) {
    for (const auto& s : ctx_.store->queryEvents(q.limit, q.before)) out.push_back(fromStored(s));
    return out;
  }
  if (!ctx_.events) return out;
  for (auto& it : ctx_.events->query(q.limit, q.before.value_or(0))) {
    web::EventRecord e;
    e.id = it.id;
    e.wall_time_s = it.wallTimeS;
    e.event = it.event;
    e.text = it.text;
    out.push_back(std::move(e));
  }
  return out;
}

web::HistoryResult WebApi::history(const web::HistoryQuery& q) {
  web::HistoryResult r;
  if (!ctx_.store) {
    r.error = "no history: the daemon runs without a state database (--state-db)";
    return r;
  }
  const auto known = ctx_.store->series();
  for (const auto& s : q.series) {
    if (std::find(known.begin(), known.end(), s) == known.end()) {
      r.error = "unknown series '" + s + "'";
      return r;
    }
  }
  // Bounds before any float -> integer conversion (docs/security.md): a
  // double outside int64's range makes that conversion undefined.
  constexpr double kMaxEpochS = 1e10;     // year 2286
  constexpr double kMaxPoints = 10000.0;  // as the web server allows
  if (!std::isfinite(q.from_s) || !std::isfinite(q.to_s) || q.from_s < 0.0 || q.to_s > kMaxEpochS) {
    r.error = "from and to must be Unix times between 0 and 1e10 s";
    return r;
  }
  if (!(q.from_s <= q.to_s)) {
    r.error = "from must be before to";
    return r;
  }
  if (!std::isfinite(q.step_s) || q.step_s < 1.0 || q.step_s > kMaxEpochS) {
    r.error = "step must be 1 s to 1e10 s";
    return r;
  }
  if ((q.to_s - q.from_s) / q.step_s > kMaxPoints) {
    r.error = "too many points: raise step or narrow from/to";
    return r;
  }
  const auto fromMs = static_cast<std::int64_t>(q.from_s * 1000.0);
  const auto toMs = static_cast<std::int64_t>(q.to_s * 1000.0);
  const auto stepMs = static_cast<std::int64_t>(q.step_s * 1000.0);
  for (std::int64_t t = fromMs; t <= toMs && r.t.size() < 100000; t += stepMs) r.t.push_back(t / 1000.0);
  for (const auto& s : q.series) {
    std::vector<double> col(r.t.size(), std::nan(""));
    for (const auto& p : ctx_.store->queryHistory(s, fromMs, toMs, stepMs)) {
      const auto i = (p.tMs - fromMs) / stepMs;
      if (i >= 0 && static_cast<std::size_t>(i) < col.size()) col[static_cast<std::size_t>(i)] = p.value;
    }
    r.series.emplace_back(s, std::move(col));
  }
  return r;
}

std::vector<web::ProbeResult> WebApi::probeResults() {
  if (ctx_.sim)
    return {{"simulated board (SimWorld)", true, "INA228 and ADS1115 chip models on a simulated I2C bus"}};
  return {};
}

namespace {
std::string utcText(std::int64_t unixMs) { return wallTimeText(unixMs, "%Y-%m-%d %H:%M UTC", TimeZone::Utc); }
}  // namespace

web::VersionMap WebApi::versions() {
  web::VersionMap v{{"xregulatord", XR_VERSION_STRING}, {"mode", ctx_.sim ? "sim" : "board"}};
  if (ctx_.update) ctx_.update->addTo(v);
  // The store's state on the System page (docs/security.md): whether changes
  // survive a restart at all.
  if (!ctx_.store) {
    v["store"] = "none: no state database, changes last for this run only";
  } else {
    const StoreService::Status st = ctx_.store->status();
    if (!st.persistent)
      v["store"] = "NOT SAVING: " + st.message + "; changes are refused";
    else if (st.restored || st.recovered)
      v["store"] = (st.restored ? "RESTORED FROM BACKUP at start: " : "RESET at start: ") + st.message;
    else
      v["store"] = "ok: " + st.path;
    v["store_backup"] = st.lastBackupMs > 0 ? st.backupPath + " of " + utcText(st.lastBackupMs) : "none yet";
  }
  return v;
}

web::Health WebApi::health() {
  web::Health h;
  const auto now = unixMsNow();
  const auto last = ctx_.lastHeartbeatWallMs ? ctx_.lastHeartbeatWallMs->load() : 0;
  const bool ticking = last > 0 && now - last < 2000;
  const bool outputsOk = !(ctx_.fieldSafeFault && ctx_.fieldSafeFault->load());
  h.ok = ticking && outputsOk;
  h.detail = !ticking ? "control loop not ticking" : (!outputsOk ? "outputs cannot be driven" : "ok");
  return h;
}

}  // namespace xr::app

// Serialisation of the daemon's structs for the web API (see json_format.h).
#include "web/server/json_format.h"

#include <cmath>
#include <cstdio>
#include <type_traits>

#include "core/modes.h"
#include "web/server/json_status.h"
#include "web/server/json_text.h"

namespace xr::web {
namespace json = boost::json;

json::value number(double v) {
  if (!std::isfinite(v)) return nullptr;
  return v;
}

namespace {

// One field of a telemetry struct for /api/status: snake_case name, flags as
// booleans, the specification's enums by name, numbers rounded (json_status.h).
struct FieldToJson {
  json::object& o;
  template <typename V>
  void operator()(const char* name, const V& v) const {
    const std::string key = snakeName(name);
    if constexpr (std::is_same_v<V, bool>) {
      o[key] = v;
    } else if constexpr (std::is_enum_v<V>) {
      o[key] = toString(v);
    } else {
      o[key] = statusNumber(key, static_cast<double>(v));
    }
  }
};

// The field lists live beside the structs (visit*Telemetry), so every field
// a module adds is exported without a second list here.
template <typename T, typename Visit>
json::object telemetryToJson(const T& t, Visit visit) {
  json::object o;
  visit(t, FieldToJson{o});
  return o;
}

json::object loopToJson(const LoopStats& l) {
  json::object o;
  o["ticks"] = l.ticks;
  o["overruns"] = l.overruns;
  o["overruns_own"] = l.overruns_own;
  for (auto [name, v] :
       {std::pair{"target_period_us", l.target_period_us}, std::pair{"period_mean_us", l.period_mean_us},
        std::pair{"period_p99_us", l.period_p99_us}, std::pair{"period_max_us", l.period_max_us},
        std::pair{"exec_mean_us", l.exec_mean_us}, std::pair{"exec_p99_us", l.exec_p99_us},
        std::pair{"exec_max_us", l.exec_max_us}, std::pair{"tick_cpu_p99_us", l.tick_cpu_p99_us},
        std::pair{"tick_cpu_max_us", l.tick_cpu_max_us}})
    o[name] = statusNumber(name, v);
  o["sensor_errors"] = l.sensor_errors;
  return o;
}

// The CSV's flags are 0/1 (docs/architecture.md "Threads"); a program reading JSON gets booleans.
json::value columnToJson(std::string_view name, const ColumnValue& v) {
  if (const auto* d = std::get_if<double>(&v)) return statusNumber(name, *d);
  if (const auto* b = std::get_if<bool>(&v)) return *b;
  return json::string(std::get<std::string_view>(v));
}

std::string_view kindName(ParamKind k) { return toString(k); }

json::value paramValue(const ParamSpec& spec, const Params& p) {
  if (spec.kind == ParamKind::Table) {
    json::array a;
    for (std::size_t i = 0; i < RPM_TABLE_SIZE; ++i) a.push_back(number(spec.get(p, i)));
    return a;
  }
  const double v = spec.get(p, 0);
  if (spec.kind == ParamKind::Bool) return v != 0.0;
  if (spec.kind == ParamKind::Int) return static_cast<std::int64_t>(std::llround(v));
  return number(v);
}

json::value paramDefault(const ParamSpec& spec) {
  if (spec.kind == ParamKind::Table) {
    json::array a;
    for (double v : spec.tableDefault) a.push_back(number(v));
    return a;
  }
  if (spec.kind == ParamKind::Bool) return spec.defaultValue != 0.0;
  if (spec.kind == ParamKind::Int) return static_cast<std::int64_t>(std::llround(spec.defaultValue));
  return number(spec.defaultValue);
}

bool sameValue(const ParamSpec& spec, const Params& a, const Params& b) {
  const std::size_t n = spec.kind == ParamKind::Table ? RPM_TABLE_SIZE : 1;
  for (std::size_t i = 0; i < n; ++i)
    if (spec.get(a, i) != spec.get(b, i)) return false;
  return true;
}

std::string promName(std::string_view col) { return "xregulator_" + std::string(col); }

void promLine(std::string& out, std::string_view name, std::string_view type, std::string_view help,
              double v) {
  char buf[64];
  out += "# HELP ";
  out += name;
  out += ' ';
  out += help;
  out += "\n# TYPE ";
  out += name;
  out += ' ';
  out += type;
  out += '\n';
  out += name;
  out += ' ';
  if (std::isnan(v))
    out += "NaN";
  else if (std::isinf(v))
    out += v > 0 ? "+Inf" : "-Inf";
  else {
    std::snprintf(buf, sizeof buf, "%.17g", v);
    out += buf;
  }
  out += '\n';
}

}  // namespace

json::object statusToJson(const StatusSnapshot& s) {
  json::object o;
  o["schema"] = kStatusSchema;
  visitTelemetryColumns(s.telemetry, s.start, [&](std::string_view name, const ColumnValue& v) {
    o[name] = columnToJson(name, v);
  });
  if (s.sim) {
    o["sim_battery_v"] = statusNumber("sim_battery_v", s.sim->battery_v);
    o["sim_alt_a"] = statusNumber("sim_alt_a", s.sim->alt_a);
    o["sim_alt_temp_f"] = statusNumber("sim_alt_temp_f", s.sim->alt_temp_f);
    o["sim_soc_pct"] = statusNumber("sim_soc_pct", s.sim->soc_pct);
    o["sim_bms_connected"] = s.sim->bms_connected;
    o["sim_field_on"] = s.sim->field_on;
  }
  // The one SoC rule (socShown, docs/batteries.md): the number and its
  // source; no number while the regulator does not know it.
  const owner::OwnerModel model = owner::ownerModel(s.telemetry, {s.setUp, s.setupLimits});
  o["soc_source"] = model.soc.source;
  o["owner"] = ownerToJson(model);
  o["seq"] = s.seq;
  o["wall_time_s"] = statusNumber("wall_time_s", s.wall_time_s);
  o["simulated"] = s.sim.has_value();
  o["control"] =
      telemetryToJson(s.telemetry.control, [](const auto& t, auto f) { visitControlTelemetry(t, f); });
  o["protection"] =
      telemetryToJson(s.telemetry.protection, [](const auto& t, auto f) { visitProtectionTelemetry(t, f); });
  o["caps"] = telemetryToJson(s.telemetry.caps, [](const auto& t, auto f) { visitCommandCaps(t, f); });
  o["battery"] =
      telemetryToJson(s.telemetry.battery, [](const auto& t, auto f) { visitBatteryTelemetry(t, f); });
  o["loop"] = loopToJson(s.loop);
  for (const auto& e : s.extras) {
    // Never let an extra replace a column or a core section.
    if (o.contains(e.section) && !o.at(e.section).is_object()) continue;
    auto& sec = o[e.section];
    if (!sec.is_object()) sec = json::object();
    const std::string key = snakeName(e.name);
    sec.as_object()[key] = statusNumber(key, e.value);
  }
  return o;
}

std::string serializeStatus(const StatusSnapshot& s) { return jsonText(statusToJson(s)); }

json::object paramsToJson(const Params& current, const Params& file,
                          const std::map<std::string, std::string>& sources,
                          const std::set<std::string>& profileOwned) {
  const Params defaults{};
  json::array list;
  for (const auto& spec : catalogue()) {
    json::object p;
    p["name"] = spec.name;
    p["group"] = toString(spec.group);
    p["kind"] = kindName(spec.kind);
    p["unit"] = spec.unit;
    p["min"] = number(spec.min);
    p["max"] = number(spec.max);
    p["help"] = spec.help;
    p["value"] = paramValue(spec, current);
    p["default"] = paramDefault(spec);
    p["file"] = paramValue(spec, file);
    p["changed"] = !sameValue(spec, current, defaults);  // differs from the catalogue default
    p["overridden"] = !sameValue(spec, current, file);   // differs from the config file (runtime override)
    p["profile_owned"] = profileOwned.contains(std::string(spec.name));
    if (auto it = sources.find(std::string(spec.name)); it != sources.end())
      p["source"] = it->second;
    else
      p["source"] = !sameValue(spec, current, file)    ? "dashboard"
                    : !sameValue(spec, file, defaults) ? "file"
                                                       : "default";
    if (!spec.choices.empty()) {
      // A named choice (BatteryProfile): its names, and the current one.
      json::array names;
      for (int i = 0; !choiceName(spec, i).empty(); ++i) names.push_back(json::string(choiceName(spec, i)));
      p["choices"] = std::move(names);
      p["value_name"] = choiceName(spec, static_cast<int>(spec.get(current, 0)));
    }
    list.push_back(std::move(p));
  }
  json::array groups;
  for (int g = 0; g <= static_cast<int>(ParamGroup::RpmTables); ++g)
    groups.push_back(json::string(toString(static_cast<ParamGroup>(g))));
  json::object o;
  o["params"] = std::move(list);
  o["groups"] = std::move(groups);
  return o;
}

json::object eventToJson(const EventRecord& r) {
  json::object o;
  o["id"] = r.id;
  o["wall_time_s"] = number(r.wall_time_s);
  o["t_s"] = number(toSec(r.event.t));
  o["level"] = toString(r.event.level);
  o["code"] = toString(r.event.code);
  o["reason"] = toString(r.event.reason);
  o["mode"] = toString(r.event.mode);
  o["a"] = number(r.event.a);
  o["b"] = number(r.event.b);
  o["detail"] = r.event.detail;
  o["text"] = r.text;
  return o;
}

json::object historyToJson(const HistoryResult& h) {
  json::object o;
  json::array t;
  // Rounded as /api/status is (json_status.h), here and in the integrations' values.
  for (double v : h.t) t.push_back(statusNumber("t_s", v));
  o["t"] = std::move(t);
  json::object series;
  for (const auto& [name, values] : h.series) {
    json::array a;
    for (double v : values) a.push_back(statusNumber(name, v));
    series[name] = std::move(a);
  }
  o["series"] = std::move(series);
  return o;
}

std::string metricsText(const StatusSnapshot* s, const WebServerStats& st) {
  std::string out;
  out.reserve(8192);
  if (s) {
    visitTelemetryColumns(s->telemetry, s->start, [&](std::string_view name, const ColumnValue& v) {
      if (const auto* d = std::get_if<double>(&v))
        promLine(out, promName(name), "gauge", "telemetry column " + std::string(name), *d);
      else if (const auto* b = std::get_if<bool>(&v))
        promLine(out, promName(name), "gauge", "telemetry flag " + std::string(name), *b ? 1.0 : 0.0);
    });
    // Names (mode, stage, reason) as info-style label sets.
    for (auto [metric, label] : {std::pair{"xregulator_mode_info", toString(s->telemetry.mode)},
                                 std::pair{"xregulator_stage_info", toString(s->telemetry.stage)},
                                 std::pair{"xregulator_reason_info", toString(s->telemetry.reason)}}) {
      out += "# TYPE ";
      out += metric;
      out += " gauge\n";
      out += metric;
      out += "{value=\"";
      out += label;
      out += "\"} 1\n";
    }
    const auto& l = s->loop;
    promLine(out, "xregulator_loop_ticks_total", "counter", "Control ticks since start",
             static_cast<double>(l.ticks));
    promLine(out, "xregulator_loop_overruns_total", "counter", "Control ticks that overran their period",
             static_cast<double>(l.overruns));
    promLine(out, "xregulator_loop_overruns_own_total", "counter",
             "Overruns caused by the daemon (a tick used a whole period of CPU)",
             static_cast<double>(l.overruns_own));
    promLine(out, "xregulator_loop_tick_cpu_max_us", "gauge", "Control tick CPU time max (us)",
             l.tick_cpu_max_us);
    promLine(out, "xregulator_loop_period_p99_us", "gauge", "Control period p99 (us)", l.period_p99_us);
    promLine(out, "xregulator_loop_period_max_us", "gauge", "Control period max (us)", l.period_max_us);
    promLine(out, "xregulator_loop_exec_p99_us", "gauge", "Control tick execution p99 (us)", l.exec_p99_us);
    promLine(out, "xregulator_sensor_errors_total", "counter", "Failed sensor reads",
             static_cast<double>(l.sensor_errors));
    promLine(out, "xregulator_telemetry_seq", "counter", "Telemetry sequence number",
             static_cast<double>(s->seq));
  }
  promLine(out, "xregulator_http_requests_total", "counter", "HTTP requests served",
           static_cast<double>(st.http_requests));
  promLine(out, "xregulator_http_errors_total", "counter", "HTTP 4xx/5xx responses",
           static_cast<double>(st.http_errors));
  promLine(out, "xregulator_ws_clients", "gauge", "WebSocket clients connected",
           static_cast<double>(st.ws_clients));
  promLine(out, "xregulator_ws_frames_sent_total", "counter", "WebSocket telemetry frames sent",
           static_cast<double>(st.ws_frames_sent));
  promLine(out, "xregulator_ws_frames_dropped_total", "counter",
           "WebSocket frames replaced by a newer one for a slow client",
           static_cast<double>(st.ws_frames_dropped));
  promLine(out, "xregulator_connections", "gauge", "Open connections", static_cast<double>(st.connections));
  promLine(out, "xregulator_connections_refused_total", "counter", "Connections refused over the cap",
           static_cast<double>(st.connections_refused));
  promLine(out, "xregulator_connections_evicted_total", "counter",
           "Connections still reading a request, closed to make room for a new one",
           static_cast<double>(st.connections_evicted));
  return out;
}

json::object canBmsToJson(const CanBmsState& b) {
  json::object o;
  o["state"] = b.state;
  o["protocol"] = b.protocol.empty() ? json::value(nullptr) : json::value(b.protocol);
  o["follow"] = b.follow;
  o["cvl_v"] = statusNumber("cvl_v", b.cvl_v);
  o["ccl_a"] = statusNumber("ccl_a", b.ccl_a);
  o["soc_pct"] = statusNumber("soc_pct", b.soc_pct);
  o["cell_max_v"] = statusNumber("cell_max_v", b.cell_max_v);
  o["age_s"] = statusNumber("age_s", b.age_s);
  o["frames"] = b.frames;
  o["bad_frames"] = b.bad_frames;
  o["error_frames"] = b.error_frames;
  o["open_failures"] = b.open_failures;
  return o;
}

json::object canN2kToJson(const CanN2kState& n) {
  json::object o;
  o["state"] = n.state;
  o["claimed"] = n.claimed;
  o["address"] = n.address < 0 ? json::value(nullptr) : json::value(n.address);
  o["tx_frames"] = n.tx_frames;
  o["rx_frames"] = n.rx_frames;
  o["error_frames"] = n.error_frames;
  o["open_failures"] = n.open_failures;
  return o;
}

json::object integrationToJson(const IntegrationState& i) {
  json::object o;
  o["name"] = i.name;
  o["enabled"] = i.enabled;
  o["connected"] = i.connected;
  o["last_error"] = i.last_error;
  o["messages_sent"] = i.messages_sent;
  o["messages_received"] = i.messages_received;
  o["messages_dropped"] = i.messages_dropped;
  o["values_refused"] = i.values_refused;
  o["outages"] = i.outages;
  if (!i.values.empty()) {
    json::object v;
    for (const auto& [k, x] : i.values) v[k] = statusNumber(k, x);
    o["values"] = std::move(v);
  }
  if (!i.texts.empty()) {
    json::object t;
    for (const auto& [k, x] : i.texts) t[k] = x;
    o["texts"] = std::move(t);
  }
  return o;
}

std::string integrationMetrics(const std::vector<IntegrationState>& list) {
  std::string out;
  struct Metric {
    const char* name;
    const char* type;
    const char* help;
    std::uint64_t (*value)(const IntegrationState&);
  };
  static const Metric kMetrics[] = {
      {"xregulator_integration_connected", "gauge", "1 when the integration is connected",
       [](const IntegrationState& i) -> std::uint64_t { return i.connected ? 1 : 0; }},
      {"xregulator_integration_messages_sent_total", "counter", "Messages sent by the integration",
       [](const IntegrationState& i) { return i.messages_sent; }},
      {"xregulator_integration_messages_dropped_total", "counter",
       "Messages replaced by a newer one while the link was busy or down",
       [](const IntegrationState& i) { return i.messages_dropped; }},
      {"xregulator_integration_values_refused_total", "counter", "Bad values from the server, refused",
       [](const IntegrationState& i) { return i.values_refused; }},
      {"xregulator_integration_outages_total", "counter", "Connections lost or never made",
       [](const IntegrationState& i) { return i.outages; }},
  };
  for (const auto& m : kMetrics) {
    bool header = false;
    for (const auto& i : list) {
      if (!i.enabled) continue;
      if (!header) {
        out += std::string("# HELP ") + m.name + " " + m.help + "\n# TYPE " + m.name + " " + m.type + "\n";
        header = true;
      }
      out += std::string(m.name) + "{integration=\"" + i.name + "\"} " + std::to_string(m.value(i)) + "\n";
    }
  }
  return out;
}

}  // namespace xr::web

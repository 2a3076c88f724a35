// HTTP routes of issue 9: /api/status, /api/params (GET, PATCH), /api/commands,
// /api/events, /api/history, /api/system, /metrics, /healthz, static files.
#include "web/server/api_handler.h"

#include <array>
#include <boost/json.hpp>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string_view>

#include "web/server/auth.h"
#include "web/server/json_format.h"
#include "web/server/static_files.h"

namespace xr::web {
namespace json = boost::json;

namespace {

constexpr std::size_t kMaxEventLimit = 1000;
constexpr std::size_t kMaxHistorySeries = 16;
constexpr double kMaxHistoryPoints = 10000.0;

Response reply(const Request& req, http::status status, std::string body,
               std::string_view contentType = "application/json") {
  Response res{status, req.version()};
  res.set(http::field::server, "xregulatord");
  res.set(http::field::content_type, contentType);
  res.set(http::field::cache_control, "no-store");
  res.set("X-Content-Type-Options", "nosniff");
  res.keep_alive(req.keep_alive());
  res.body() = std::move(body);
  res.prepare_payload();
  return res;
}

Response jsonReply(const Request& req, http::status status, const json::value& v) {
  return reply(req, status, json::serialize(v));
}

Response error(const Request& req, http::status status, std::string_view message) {
  json::object o;
  o["error"] = message;
  auto res = jsonReply(req, status, o);
  if (status == http::status::unauthorized)
    res.set(http::field::www_authenticate, "Bearer realm=\"xregulator\"");
  return res;
}

Response authError(const Request& req, unsigned code) {
  return code == 401
             ? error(req, http::status::unauthorized, "missing token: send Authorization: Bearer <token>")
             : error(req, http::status::forbidden, "invalid token");
}

double nowEpochS() {
  using namespace std::chrono;
  return duration<double>(system_clock::now().time_since_epoch()).count();
}

std::optional<double> parseDouble(std::string_view s) {
  if (s.empty()) return std::nullopt;
  double v = 0;
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc{} || p != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

std::optional<std::int64_t> parseInt(std::string_view s) {
  if (s.empty()) return std::nullopt;
  std::int64_t v = 0;
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc{} || p != s.data() + s.size()) return std::nullopt;
  return v;
}

// A JSON number as double (int64, uint64 or double), nullopt otherwise.
std::optional<double> jsonNumber(const json::value& v) {
  if (v.is_double()) return v.get_double();
  if (v.is_int64()) return static_cast<double>(v.get_int64());
  if (v.is_uint64()) return static_cast<double>(v.get_uint64());
  return std::nullopt;
}

std::string plain(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string rangeText(const ParamSpec& spec) {
  return "must be between " + plain(spec.min) + " and " + plain(spec.max) +
         (spec.unit.empty() ? "" : " " + std::string(spec.unit));
}

// One scalar value for spec, or an error message.
std::optional<double> scalarFor(const ParamSpec& spec, const json::value& v, std::string& err) {
  std::optional<double> d;
  if (spec.kind == ParamKind::Bool && v.is_bool())
    d = v.get_bool() ? 1.0 : 0.0;
  else
    d = jsonNumber(v);
  if (!d) {
    err = spec.kind == ParamKind::Bool ? "expected true/false (or 0/1)" : "expected a number";
    return std::nullopt;
  }
  if (!std::isfinite(*d)) {
    err = "expected a finite number";
    return std::nullopt;
  }
  if ((spec.kind == ParamKind::Int || spec.kind == ParamKind::Bool) && std::trunc(*d) != *d) {
    err = "expected a whole number";
    return std::nullopt;
  }
  if (!valueFits(spec, *d)) {
    err = spec.kind == ParamKind::Bool ? "expected true/false (or 0/1)" : rangeText(spec);
    return std::nullopt;
  }
  return d;
}

Response patchErrors(const Request& req, const std::vector<FieldError>& errors) {
  json::object errs;
  for (const auto& e : errors) errs[e.name] = e.message;
  json::object o;
  o["error"] = errors.size() == 1 ? "1 parameter rejected; nothing applied"
                                  : std::to_string(errors.size()) + " parameters rejected; nothing applied";
  o["errors"] = std::move(errs);
  return jsonReply(req, http::status::bad_request, o);
}

std::optional<json::value> parseBody(const Request& req, std::string& err) {
  boost::system::error_code ec;
  json::parse_options po;
  po.max_depth = 16;
  json::value v = json::parse(req.body(), ec, {}, po);
  if (ec) {
    err = "malformed JSON: " + ec.message();
    return std::nullopt;
  }
  return v;
}

constexpr std::array kAllCommands{
    CommandType::Auto,
    CommandType::Manual,
    CommandType::Off,
    CommandType::LimpHome,
    CommandType::LimpHomeOff,
    CommandType::ReenableField,
    CommandType::ResetAlarmLatch,
    CommandType::ResetSocGain,
    CommandType::ResetAltZero,
    CommandType::SetSoc,
    CommandType::SystemIdStart,
    CommandType::TuningCommit,
    CommandType::CvTuningCommit,
    CommandType::WeatherMode,
};

}  // namespace

std::string percentDecode(std::string_view s, bool* ok) {
  std::string out;
  out.reserve(s.size());
  bool good = true;
  auto hex = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  };
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '+') {
      out.push_back(' ');
    } else if (s[i] == '%') {
      if (i + 2 >= s.size()) {
        good = false;
        break;
      }
      const int hi = hex(s[i + 1]), lo = hex(s[i + 2]);
      if (hi < 0 || lo < 0) {
        good = false;
        break;
      }
      out.push_back(static_cast<char>(hi * 16 + lo));
      i += 2;
    } else {
      out.push_back(s[i]);
    }
  }
  if (ok) *ok = good;
  return out;
}

std::optional<std::string> queryParam(std::string_view query, std::string_view key) {
  while (!query.empty()) {
    const auto amp = query.find('&');
    const std::string_view pair = query.substr(0, amp);
    const auto eq = pair.find('=');
    const std::string_view k = pair.substr(0, eq);
    if (k == key)
      return percentDecode(eq == std::string_view::npos ? std::string_view{} : pair.substr(eq + 1));
    if (amp == std::string_view::npos) break;
    query.remove_prefix(amp + 1);
  }
  return std::nullopt;
}

ApiHandler::ApiHandler(DaemonApi& api, const WebServerOptions& opts, std::function<WebServerStats()> stats)
    : api_(api), opts_(opts), stats_(std::move(stats)) {}

unsigned ApiHandler::checkRead(std::string_view authorization, std::string_view queryToken) const {
  if (!opts_.reads_require_token) return 0;
  switch (checkBearer(authorization, queryToken, opts_.token)) {
    case AuthResult::Ok:
      return 0;
    case AuthResult::Missing:
      return 401;
    case AuthResult::Forbidden:
      return 403;
  }
  return 403;
}

std::shared_ptr<const std::string> ApiHandler::statusText(std::uint64_t* seqOut) {
  StatusSnapshot snap;
  if (!api_.latestStatus(snap) || snap.seq == 0) return nullptr;
  {
    std::lock_guard lock(cacheMutex_);
    if (cached_ && cachedSeq_ == snap.seq) {
      if (seqOut) *seqOut = snap.seq;
      return cached_;
    }
  }
  auto text = std::make_shared<const std::string>(serializeStatus(snap));
  std::lock_guard lock(cacheMutex_);
  if (snap.seq >= cachedSeq_) {
    cachedSeq_ = snap.seq;
    cached_ = text;
  }
  if (seqOut) *seqOut = snap.seq;
  return text;
}

Response ApiHandler::handle(const Request& req) {
  Response res;
  try {
    res = route(req);
  } catch (const std::exception& e) {
    // A bug must cost one request, never the daemon (and never the field).
    res = error(req, http::status::internal_server_error, std::string("internal error: ") + e.what());
  }
  // HEAD: the headers GET would send, never a body (issue 26, item 12: a
  // body here desynchronises a pipelining client).
  if (req.method() == http::verb::head && !res.body().empty()) {
    const auto len = res.body().size();
    res.body().clear();
    res.content_length(len);
  }
  return res;
}

Response ApiHandler::route(const Request& req) {
  const std::string_view target = req.target();
  const auto qpos = target.find('?');
  const std::string_view path = target.substr(0, qpos);
  const std::string_view query =
      qpos == std::string_view::npos ? std::string_view{} : target.substr(qpos + 1);
  const auto method = req.method();
  const bool isGet = method == http::verb::get || method == http::verb::head;

  auto onlyGet = [&](auto fn) -> Response {
    if (!isGet) {
      auto r = error(req, http::status::method_not_allowed, "method not allowed");
      r.set(http::field::allow, "GET, HEAD");
      return r;
    }
    if (auto code = checkRead(req[http::field::authorization], queryParam(query, "token").value_or(""));
        code != 0)
      return authError(req, code);
    return fn();
  };

  if (path == "/healthz") {
    if (!isGet) return error(req, http::status::method_not_allowed, "method not allowed");
    return getHealth(req);
  }
  if (path == "/api/status") return onlyGet([&] { return getStatus(req); });
  if (path == "/api/events") return onlyGet([&] { return getEvents(req, query); });
  if (path == "/api/history") return onlyGet([&] { return getHistory(req, query); });
  if (path == "/api/system") return onlyGet([&] { return getSystem(req); });
  if (path == "/metrics") return onlyGet([&] { return getMetrics(req); });
  if (path == "/api/params" || path == "/api/commands") {
    const bool isParams = path == "/api/params";
    if (isGet) return onlyGet([&] { return isParams ? getParams(req) : getCommands(req); });
    const auto write = isParams ? http::verb::patch : http::verb::post;
    if (method != write) {
      auto r = error(req, http::status::method_not_allowed, "method not allowed");
      r.set(http::field::allow, isParams ? "GET, HEAD, PATCH" : "GET, HEAD, POST");
      return r;
    }
    // Every write needs the token, whatever reads_require_token says.
    switch (checkBearer(req[http::field::authorization], "", opts_.token)) {
      case AuthResult::Missing:
        return authError(req, 401);
      case AuthResult::Forbidden:
        return authError(req, 403);
      case AuthResult::Ok:
        break;
    }
    return isParams ? patchParams(req) : postCommand(req);
  }
  if (path == "/ws") return error(req, http::status::upgrade_required, "WebSocket upgrade required");
  if (path.starts_with("/api/")) return error(req, http::status::not_found, "no such endpoint");
  if (!isGet) return error(req, http::status::method_not_allowed, "method not allowed");
  return getStatic(req, path);
}

Response ApiHandler::getStatus(const Request& req) {
  auto text = statusText();
  if (!text) return error(req, http::status::service_unavailable, "no telemetry yet");
  return reply(req, http::status::ok, *text);
}

Response ApiHandler::getParams(const Request& req) {
  return jsonReply(req, http::status::ok, paramsToJson(api_.currentParams(), api_.fileParams()));
}

Response ApiHandler::patchParams(const Request& req) {
  std::string err;
  auto body = parseBody(req, err);
  if (!body) return error(req, http::status::bad_request, err);
  if (!body->is_object())
    return error(req, http::status::bad_request, "expected a JSON object of parameter name -> value");
  const auto& obj = body->get_object();
  if (obj.empty()) return error(req, http::status::bad_request, "no parameters given");

  std::vector<FieldError> errors;
  std::vector<ParamChange> changes;
  for (const auto& kv : obj) {
    const std::string name(kv.key());
    const ParamSpec* spec = findParam(name);
    if (!spec) {
      errors.push_back({name, "unknown parameter"});
      continue;
    }
    if (spec->kind == ParamKind::Table) {
      if (!kv.value().is_array() || kv.value().get_array().size() != RPM_TABLE_SIZE) {
        errors.push_back({name, "expected an array of " + std::to_string(RPM_TABLE_SIZE) + " numbers"});
        continue;
      }
      const auto& arr = kv.value().get_array();
      std::string e;
      for (std::size_t i = 0; i < arr.size() && e.empty(); ++i) {
        auto d = scalarFor(*spec, arr[i], e);
        if (d)
          changes.push_back({spec, static_cast<int>(i), *d});
        else
          e = "element " + std::to_string(i) + ": " + e;
      }
      if (!e.empty()) errors.push_back({name, e});
      continue;
    }
    std::string e;
    if (auto d = scalarFor(*spec, kv.value(), e))
      changes.push_back({spec, -1, *d});
    else
      errors.push_back({name, e});
  }
  if (!errors.empty()) return patchErrors(req, errors);

  PatchResult result = api_.patchParams(changes);
  if (!result.errors.empty()) return patchErrors(req, result.errors);
  json::array applied;
  for (const auto& kv : obj) applied.push_back(json::string(kv.key()));
  json::object o;
  o["ok"] = true;
  o["applied"] = std::move(applied);
  return jsonReply(req, http::status::ok, o);
}

Response ApiHandler::postCommand(const Request& req) {
  std::string err;
  auto body = parseBody(req, err);
  if (!body) return error(req, http::status::bad_request, err);
  if (!body->is_object())
    return error(req, http::status::bad_request, "expected a JSON object {\"command\": ...}");
  const auto& obj = body->get_object();
  const auto* name = obj.if_contains("command");
  if (!name || !name->is_string())
    return error(req, http::status::bad_request, "\"command\" must be a string");
  const auto type = parseCommandType(std::string_view(name->get_string()));
  if (!type)
    return error(req, http::status::bad_request, "unknown command '" + std::string(name->get_string()) + "'");
  const std::string_view arg = commandArgument(*type);
  for (const auto& kv : obj)
    if (kv.key() != "command" && kv.key() != arg)
      return error(
          req, http::status::bad_request,
          "unknown field '" + std::string(kv.key()) + "' for command '" + std::string(toString(*type)) + "'");
  Command cmd;
  cmd.type = *type;
  if (!arg.empty()) {
    const auto* v = obj.if_contains(arg);
    if (!v)
      return error(req, http::status::bad_request,
                   "command '" + std::string(toString(*type)) + "' needs '" + std::string(arg) + "'");
    if (arg == "active") {
      if (!v->is_bool()) return error(req, http::status::bad_request, "'active' must be true or false");
      cmd.flag = v->get_bool();
    } else {
      auto d = jsonNumber(*v);
      if (!d || !std::isfinite(*d))
        return error(req, http::status::bad_request, "'" + std::string(arg) + "' must be a number");
      if (*d < 0.0 || *d > 100.0)
        return error(req, http::status::bad_request,
                     "'" + std::string(arg) + "' must be between 0 and 100 %");
      cmd.value = *d;
    }
  }
  CommandResult r = api_.command(cmd);
  json::object o;
  o["ok"] = r.accepted;
  o["command"] = toString(cmd.type);
  o["message"] = r.message;
  if (!r.accepted) o["error"] = r.message.empty() ? "command refused" : r.message;
  return jsonReply(req, r.accepted ? http::status::ok : http::status::conflict, o);
}

Response ApiHandler::getCommands(const Request& req) {
  json::array a;
  for (auto t : kAllCommands) {
    json::object c;
    c["command"] = toString(t);
    c["argument"] = commandArgument(t);
    a.push_back(std::move(c));
  }
  json::object o;
  o["commands"] = std::move(a);
  return jsonReply(req, http::status::ok, o);
}

Response ApiHandler::getEvents(const Request& req, std::string_view query) {
  EventQuery q;
  if (auto s = queryParam(query, "limit")) {
    auto v = parseInt(*s);
    if (!v || *v < 1) return error(req, http::status::bad_request, "limit must be a positive whole number");
    q.limit = static_cast<std::size_t>(std::min<std::int64_t>(*v, kMaxEventLimit));
  }
  if (auto s = queryParam(query, "before")) {
    auto v = parseInt(*s);
    if (!v) return error(req, http::status::bad_request, "before must be an event id (whole number)");
    q.before = *v;
  }
  json::array a;
  for (const auto& e : api_.events(q)) a.push_back(eventToJson(e));
  json::object o;
  o["events"] = std::move(a);
  return jsonReply(req, http::status::ok, o);
}

Response ApiHandler::getHistory(const Request& req, std::string_view query) {
  HistoryQuery q;
  const auto series = queryParam(query, "series");
  if (!series || series->empty())
    return error(req, http::status::bad_request, "series is required (comma-separated column names)");
  std::string_view rest = *series;
  while (true) {
    const auto comma = rest.find(',');
    const std::string_view one = rest.substr(0, comma);
    if (one.empty()) return error(req, http::status::bad_request, "empty series name");
    q.series.emplace_back(one);
    if (q.series.size() > kMaxHistorySeries)
      return error(req, http::status::bad_request, "at most 16 series per request");
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  const double now = nowEpochS();
  // Times are Unix epoch seconds; zero or negative means relative to now.
  auto timeParam = [&](std::string_view key, double dflt, double& out) -> bool {
    const auto s = queryParam(query, key);
    if (!s) {
      out = dflt;
      return true;
    }
    const auto v = parseDouble(*s);
    if (!v) return false;
    out = *v <= 0.0 ? now + *v : *v;
    return true;
  };
  if (!timeParam("to", now, q.to_s)) return error(req, http::status::bad_request, "to must be a number");
  if (!timeParam("from", q.to_s - 3600.0, q.from_s))
    return error(req, http::status::bad_request, "from must be a number");
  if (!(q.from_s < q.to_s)) return error(req, http::status::bad_request, "from must be before to");
  q.step_s = std::max(1.0, (q.to_s - q.from_s) / 600.0);
  if (auto s = queryParam(query, "step")) {
    const auto v = parseDouble(*s);
    if (!v || *v <= 0.0)
      return error(req, http::status::bad_request, "step must be a positive number of seconds");
    q.step_s = *v;
  }
  if ((q.to_s - q.from_s) / q.step_s > kMaxHistoryPoints)
    return error(req, http::status::bad_request, "too many points: raise step or narrow from/to");
  HistoryResult r = api_.history(q);
  if (!r.error.empty()) return error(req, http::status::bad_request, r.error);
  auto o = historyToJson(r);
  o["from"] = q.from_s;
  o["to"] = q.to_s;
  o["step"] = q.step_s;
  return jsonReply(req, http::status::ok, o);
}

Response ApiHandler::getSystem(const Request& req) {
  json::object o;
  json::object v;
  for (const auto& [k, val] : api_.versions()) v[k] = val;
  o["versions"] = std::move(v);
  json::array probes;
  for (const auto& p : api_.probeResults()) {
    json::object j;
    j["device"] = p.device;
    j["ok"] = p.ok;
    j["detail"] = p.detail;
    probes.push_back(std::move(j));
  }
  o["probes"] = std::move(probes);
  StatusSnapshot snap;
  if (api_.latestStatus(snap)) {
    auto status = statusToJson(snap);
    o["loop"] = status["loop"];
    o["simulated"] = status["simulated"];
  }
  if (stats_) {
    const auto s = stats_();
    json::object w;
    w["http_requests"] = s.http_requests;
    w["http_errors"] = s.http_errors;
    w["ws_clients"] = s.ws_clients;
    w["ws_frames_sent"] = s.ws_frames_sent;
    w["ws_frames_dropped"] = s.ws_frames_dropped;
    w["connections"] = s.connections;
    w["connections_refused"] = s.connections_refused;
    o["web"] = std::move(w);
  }
  o["telemetry_rate_hz"] = opts_.telemetry_rate_hz;
  o["reads_require_token"] = opts_.reads_require_token;
  return jsonReply(req, http::status::ok, o);
}

Response ApiHandler::getMetrics(const Request& req) {
  StatusSnapshot snap;
  const bool have = api_.latestStatus(snap) && snap.seq != 0;
  const WebServerStats s = stats_ ? stats_() : WebServerStats{};
  return reply(req, http::status::ok, metricsText(have ? &snap : nullptr, s),
               "text/plain; version=0.0.4; charset=utf-8");
}

Response ApiHandler::getHealth(const Request& req) {
  const Health h = api_.health();
  json::object o;
  o["ok"] = h.ok;
  o["detail"] = h.detail;
  return jsonReply(req, h.ok ? http::status::ok : http::status::service_unavailable, o);
}

Response ApiHandler::getStatic(const Request& req, std::string_view path) {
  auto file = resolveStaticPath(opts_.www_root, path);
  // uPlot is copied from npm into the build/installed assets, not the source
  // tree: when www_root is the source web/www, take vendor/ from there.
  if (!file && path.starts_with("/vendor/")) file = resolveStaticPath(defaultWwwRoot(), path);
  if (!file) return error(req, http::status::not_found, "not found");
  auto content = readFile(*file);
  if (!content) return error(req, http::status::not_found, "not found");
  auto res = reply(req, http::status::ok, std::move(*content), mimeType(*file));
  res.set(http::field::cache_control, "no-cache");
  if (req.method() == http::verb::head) {
    const auto len = res.body().size();
    res.body().clear();
    res.content_length(len);
  }
  return res;
}

}  // namespace xr::web

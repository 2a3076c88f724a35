// HTTP routes (docs/dashboard.md "API"): /api/status, /api/params (GET, PATCH), /api/commands, /api/dvcc,
// /api/events, /api/history, /api/system, /api/setup/hardware, /metrics, /healthz, static files.
// This file routes a request and answers the status, system, metrics, health
// and static-file reads; the parameter, command and events/history routes
// live in api_params.cpp, api_commands.cpp and api_history.cpp.
#include "web/server/api_handler.h"

#include <boost/json.hpp>
#include <string_view>

#include "web/server/api_reply.h"
#include "web/server/auth.h"
#include "web/server/json_format.h"
#include "web/server/static_files.h"

namespace xr::web {

using namespace api;

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
    : api_(api), opts_(opts), stats_(std::move(stats)), pairing_(opts.auth_store) {}

unsigned ApiHandler::checkRead(std::string_view authorization, std::string_view queryToken) const {
  if (!opts_.reads_require_token) return 0;
  switch (checkBearer(authorization, queryToken, opts_.token)) {
    case AuthResult::Ok:
      return 0;
    case AuthResult::Missing:
      return 401;
    case AuthResult::Forbidden:
      break;
  }
  return pairing_.isDeviceToken(authorization.empty() ? queryToken : bearerToken(authorization)) ? 0 : 403;
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

Response ApiHandler::handle(const Request& req, const Peer& peer) {
  Response res;
  try {
    res = route(req, peer);
  } catch (const std::exception& e) {
    // A bug must cost one request, never the daemon (and never the field).
    res = error(req, http::status::internal_server_error, std::string("internal error: ") + e.what());
  }
  // HEAD: the headers GET would send, never a body (a
  // body here desynchronises a pipelining client).
  if (req.method() == http::verb::head && !res.body().empty()) {
    const auto len = res.body().size();
    res.body().clear();
    res.content_length(len);
  }
  return res;
}

Response ApiHandler::route(const Request& req, const Peer& peer) {
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
  if (path == "/api/history/days") return onlyGet([&] { return getHistoryDays(req, query); });
  if (path == "/api/history/charges") return onlyGet([&] { return getHistoryCharges(req, query); });
  if (path == "/api/history/trends") return onlyGet([&] { return getHistoryTrends(req, query); });
  if (path == "/api/history/export") return onlyGet([&] { return getHistoryExport(req, query); });
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
    // Every write needs a token, whatever reads_require_token says.
    if (auto code = checkWrite(req[http::field::authorization])) return authError(req, code);
    return isParams ? patchParams(req) : postCommand(req);
  }
  if (path == "/api/dvcc") {
    if (method != http::verb::post) {
      auto r = error(req, http::status::method_not_allowed, "method not allowed");
      r.set(http::field::allow, "POST");
      return r;
    }
    if (auto code = checkWrite(req[http::field::authorization])) return authError(req, code);
    return postDvcc(req);
  }
  if (path == "/api/setup/hardware") {
    if (isGet) return onlyGet([&] { return getHardwareSetup(req); });
    if (method != http::verb::put) {
      auto r = error(req, http::status::method_not_allowed, "method not allowed");
      r.set(http::field::allow, "GET, HEAD, PUT");
      return r;
    }
    if (auto code = checkWrite(req[http::field::authorization])) return authError(req, code);
    return putHardwareSetup(req);
  }
  if (path == "/api/pair" || path.starts_with("/api/pair/")) return pairRoutes(req, path, peer);
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
    w["connections_evicted"] = s.connections_evicted;
    o["web"] = std::move(w);
  }
  json::array integrations;
  for (const auto& i : api_.integrations()) integrations.push_back(integrationToJson(i));
  o["integrations"] = std::move(integrations);
  const CanState can = api_.can();
  o["bms"] = canBmsToJson(can.bms);
  o["n2k"] = canN2kToJson(can.n2k);
  o["telemetry_rate_hz"] = opts_.telemetry_rate_hz;
  o["reads_require_token"] = opts_.reads_require_token;
  return jsonReply(req, http::status::ok, o);
}

Response ApiHandler::getMetrics(const Request& req) {
  StatusSnapshot snap;
  const bool have = api_.latestStatus(snap) && snap.seq != 0;
  const WebServerStats s = stats_ ? stats_() : WebServerStats{};
  return reply(req, http::status::ok,
               metricsText(have ? &snap : nullptr, s) + integrationMetrics(api_.integrations()),
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

// GET /api/events and /api/history: paged event log and binned chart
// history, with the query limits that keep one request cheap.
#include <algorithm>
#include <boost/json.hpp>
#include <chrono>
#include <cstdint>
#include <optional>
#include <string_view>

#include "web/server/api_handler.h"
#include "web/server/api_reply.h"
#include "web/server/json_format.h"
#include "web/server/json_status.h"

namespace xr::web {

using namespace api;

namespace {

constexpr std::size_t kMaxEventLimit = 1000;
constexpr std::size_t kMaxHistorySeries = 16;
constexpr double kMaxHistoryPoints = 10000.0;

double nowEpochS() {
  using namespace std::chrono;
  return duration<double>(system_clock::now().time_since_epoch()).count();
}

}  // namespace

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
  o["from"] = statusNumber("t_s", q.from_s);
  o["to"] = statusNumber("t_s", q.to_s);
  o["step"] = statusNumber("step_s", q.step_s);
  return jsonReply(req, http::status::ok, o);
}

// ---------------------------------------------------------------- summaries

namespace {

constexpr std::int64_t kMaxSummaryRows = 366;

double hours(double s) { return s / 3600.0; }

json::object dayToJson(const DaySummary& d) {
  json::object o;
  o["day"] = d.day;
  o["alt_ah"] = statusNumber("alt_ah", d.altAh);
  o["alt_wh"] = statusNumber("alt_wh", d.altWh);
  o["battery_ah_in"] = statusNumber("battery_ah_in", d.batteryAhIn);
  o["battery_ah_out"] = statusNumber("battery_ah_out", d.batteryAhOut);
  o["bulk_h"] = statusNumber("bulk_h", hours(d.bulkS));
  o["absorption_h"] = statusNumber("absorption_h", hours(d.absorptionS));
  o["float_h"] = statusNumber("float_h", hours(d.floatS));
  o["resting_h"] = statusNumber("resting_h", hours(d.idleS));
  o["field_on_h"] = statusNumber("field_on_h", hours(d.fieldOnS));
  o["peak_alt_temp_c"] = statusNumber("peak_alt_temp_c", d.peakAltTempC);
  o["min_soc_pct"] = statusNumber("min_soc_pct", d.minSocPct);
  o["max_soc_pct"] = statusNumber("max_soc_pct", d.maxSocPct);
  o["battery_wh_in"] = statusNumber("battery_wh_in", d.batteryWhIn);
  o["v_min"] = statusNumber("v_min", d.minBatteryV);
  o["v_max"] = statusNumber("v_max", d.maxBatteryV);
  o["soc_start_pct"] = statusNumber("soc_start_pct", d.socStartPct);
  o["soc_end_pct"] = statusNumber("soc_end_pct", d.socEndPct);
  o["engine_h"] = statusNumber("engine_h", hours(d.engineS));
  return o;
}

json::object chargeToJson(const ChargeSummary& c) {
  json::object o;
  o["id"] = c.id;
  o["start_s"] = statusNumber("start_s", static_cast<double>(c.startMs) / 1000.0);
  o["end_s"] = statusNumber("end_s", static_cast<double>(c.endMs) / 1000.0);
  o["bulk_min"] = statusNumber("bulk_min", c.bulkS / 60.0);
  o["absorption_min"] = statusNumber("absorption_min", c.absorptionS / 60.0);
  o["float_min"] = statusNumber("float_min", c.floatS / 60.0);
  o["alt_ah"] = statusNumber("alt_ah", c.altAh);
  o["alt_wh"] = statusNumber("alt_wh", c.altWh);
  o["start_soc_pct"] = statusNumber("start_soc_pct", c.startSocPct);
  o["end_soc_pct"] = statusNumber("end_soc_pct", c.endSocPct);
  o["ended_by"] = c.open ? json::value(nullptr) : json::value(c.endReason);
  o["open"] = c.open;
  return o;
}

// ?n= (days) or ?limit= (charges): 1 to kMaxSummaryRows, dflt when absent.
std::optional<std::size_t> rowsParam(std::string_view query, std::string_view key, std::size_t dflt) {
  const auto s = queryParam(query, key);
  if (!s) return dflt;
  const auto v = parseInt(*s);
  if (!v || *v < 1 || *v > kMaxSummaryRows) return std::nullopt;
  return static_cast<std::size_t>(*v);
}

}  // namespace

Response ApiHandler::getHistoryDays(const Request& req, std::string_view query) {
  const auto n = rowsParam(query, "n", 30);
  if (!n) return error(req, http::status::bad_request, "n must be a whole number from 1 to 366");
  json::array a;
  for (const auto& d : api_.historyDays(*n)) a.push_back(dayToJson(d));
  json::object o;
  o["days"] = std::move(a);
  return jsonReply(req, http::status::ok, o);
}

Response ApiHandler::getHistoryCharges(const Request& req, std::string_view query) {
  if (const auto day = queryParam(query, "day")) {
    const auto list = api_.historyChargesOn(*day);
    if (!list) return error(req, http::status::bad_request, "day must be a calendar day, YYYY-MM-DD");
    json::array a;
    for (const auto& c : *list) a.push_back(chargeToJson(c));
    json::object o;
    o["day"] = *day;
    o["charges"] = std::move(a);
    return jsonReply(req, http::status::ok, o);
  }
  const auto n = rowsParam(query, "limit", 20);
  if (!n) return error(req, http::status::bad_request, "limit must be a whole number from 1 to 366");
  json::array a;
  for (const auto& c : api_.historyCharges(*n)) a.push_back(chargeToJson(c));
  json::object o;
  o["charges"] = std::move(a);
  return jsonReply(req, http::status::ok, o);
}

}  // namespace xr::web

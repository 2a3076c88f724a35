// GET /api/history/trends and /api/history/export: the trends over a season
// (docs/dashboard.md "Trends") as JSON columns for the chart, and any range
// of them as CSV for a spreadsheet. Bounds are checked before the store is
// asked, so one request stays cheap: at most ~10 000 rows either way.
#include <boost/json.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <string>

#include "web/server/api_handler.h"
#include "web/server/api_reply.h"
#include "web/server/json_status.h"
#include "web/server/json_text.h"

namespace xr::web {

using namespace api;

namespace {

constexpr double kMaxTimeS = 4102444800.0;  // 2100-01-01: later is a typing mistake
constexpr double kMaxHourlySpanS = 800.0 * 86400.0;
constexpr double kMaxDailySpanS = 36600.0 * 86400.0;

struct TrendRange {
  std::int64_t fromS = 0, toS = 0;
  bool daily = false;
  std::string error;  // non-empty: 400
};

// from/to: Unix seconds, zero or negative relative to now (as /api/history);
// step: hour or day (default: hour up to 62 days, else day).
TrendRange trendRange(std::string_view query, double defaultSpanS) {
  TrendRange r;
  const double now =
      std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  auto time = [&](std::string_view key, double dflt, double& out) {
    const auto s = queryParam(query, key);
    if (!s) return (out = dflt), true;
    const auto v = parseDouble(*s);
    if (!v) return false;
    out = *v <= 0.0 ? now + *v : *v;
    return out >= 0.0 && out <= kMaxTimeS;
  };
  double to = 0.0, from = 0.0;
  if (!time("to", now, to))
    return (r.error = "to must be Unix seconds (1970 to 2100), or <= 0 for now minus"), r;
  if (!time("from", to - defaultSpanS, from))
    return (r.error = "from must be Unix seconds (1970 to 2100), or <= 0 for now minus"), r;
  if (!(from < to)) return (r.error = "from must be before to"), r;
  const auto step = queryParam(query, "step");
  if (step && *step != "hour" && *step != "day") return (r.error = "step must be hour or day"), r;
  r.daily = step ? *step == "day" : to - from > 62.0 * 86400.0;
  if (to - from > (r.daily ? kMaxDailySpanS : kMaxHourlySpanS))
    return (r.error = r.daily ? "at most 36600 days per request" : "at most 800 days of hours: use step=day"),
           r;
  r.fromS = static_cast<std::int64_t>(std::floor(from));
  r.toS = static_cast<std::int64_t>(std::floor(to));
  return r;
}

std::string utcText(std::int64_t s) {
  const std::time_t t = static_cast<std::time_t>(s);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

// One CSV cell: the JSON number's rounding, empty when not known.
std::string cell(std::string_view name, double v) {
  const json::value j = statusNumber(name, v);
  return j.is_null() ? std::string() : jsonText(j);  // plain decimals, never 1.2E1
}

}  // namespace

Response ApiHandler::getHistoryTrends(const Request& req, std::string_view query) {
  const TrendRange r = trendRange(query, 7.0 * 86400.0);
  if (!r.error.empty()) return error(req, http::status::bad_request, r.error);
  const auto rows = api_.historyTrends(r.fromS, r.toS, r.daily);
  json::array t, samples;
  json::object series;
  for (std::size_t i = 0; i < kTrendSeriesCount; ++i) {
    const std::string name(kTrendSeries[i].name);
    json::array mn, mean, mx;
    for (const auto& row : rows) {
      mn.push_back(statusNumber(name + "_min", row.stat[i].min));
      mean.push_back(statusNumber(name + "_mean", row.stat[i].mean));
      mx.push_back(statusNumber(name + "_max", row.stat[i].max));
    }
    json::object s;
    s["unit"] = kTrendSeries[i].unit;
    s["min"] = std::move(mn);
    s["mean"] = std::move(mean);
    s["max"] = std::move(mx);
    series[name] = std::move(s);
  }
  for (const auto& row : rows) {
    t.push_back(row.startS);
    samples.push_back(row.samples);
  }
  json::object o;
  o["from"] = r.fromS;
  o["to"] = r.toS;
  o["step"] = r.daily ? "day" : "hour";
  o["t"] = std::move(t);
  o["samples"] = std::move(samples);
  o["series"] = std::move(series);
  return jsonReply(req, http::status::ok, o);
}

Response ApiHandler::getHistoryExport(const Request& req, std::string_view query) {
  const TrendRange r = trendRange(query, 30.0 * 86400.0);
  if (!r.error.empty()) return error(req, http::status::bad_request, r.error);
  std::string csv = "time_utc,time_unix_s,samples";
  for (const auto& s : kTrendSeries)
    for (const char* k : {"_min", "_mean", "_max"}) csv += "," + std::string(s.name) + k;
  csv += "\r\n";
  for (const auto& row : api_.historyTrends(r.fromS, r.toS, r.daily)) {
    csv += utcText(row.startS) + "," + std::to_string(row.startS) + "," + std::to_string(row.samples);
    for (std::size_t i = 0; i < kTrendSeriesCount; ++i) {
      const std::string name(kTrendSeries[i].name);
      csv += "," + cell(name + "_min", row.stat[i].min) + "," + cell(name + "_mean", row.stat[i].mean) + "," +
             cell(name + "_max", row.stat[i].max);
    }
    csv += "\r\n";
  }
  Response res = reply(req, http::status::ok, std::move(csv), "text/csv; charset=utf-8");
  res.set(http::field::content_disposition, "attachment; filename=\"xregulator-" +
                                                utcText(r.fromS).substr(0, 10) + "-" +
                                                (r.daily ? "daily" : "hourly") + ".csv\"");
  return res;
}

}  // namespace xr::web

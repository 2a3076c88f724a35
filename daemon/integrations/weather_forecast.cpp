#include "integrations/weather_forecast.h"

#include <boost/json.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <utility>

namespace xr::integrations {
namespace json = boost::json;

namespace {

// The UV index of a real day is 0 to about 20; 30 leaves room for the
// highest ever measured and refuses a server that sends nonsense.
constexpr double kUvMax = 30.0;
constexpr double kRadiationMaxMJm2 = 50.0;  // above the solar constant over a day

const json::array* arrayAt(const json::object& daily, const char* key) {
  const auto* v = daily.if_contains(key);
  return v ? v->if_array() : nullptr;
}

// nullopt for null; false when the value is neither null nor a number in range.
bool numberOrNull(const json::value& v, double hi, std::optional<double>& out) {
  if (v.is_null()) {
    out.reset();
    return true;
  }
  if (!v.is_number()) return false;
  const double x = v.to_number<double>();
  if (!std::isfinite(x) || x < 0.0 || x > hi) return false;
  out = x;
  return true;
}

// Days since 1970-01-01 of "YYYY-MM-DD"; nullopt when it is not such a date.
std::optional<std::int64_t> dayNumber(const std::string& text) {
  unsigned y = 0, m = 0, d = 0;
  char tail = 0;
  if (text.size() != 10 || std::sscanf(text.c_str(), "%4u-%2u-%2u%c", &y, &m, &d, &tail) != 3)
    return std::nullopt;
  const std::chrono::year_month_day ymd{std::chrono::year(static_cast<int>(y)), std::chrono::month(m),
                                        std::chrono::day(d)};
  if (!ymd.ok()) return std::nullopt;
  return std::chrono::sys_days(ymd).time_since_epoch().count();
}

}  // namespace

std::string forecastMismatch(const Forecast& f, double latitude, double longitude, std::int64_t unixNowS) {
  if (!f.latitude || !f.longitude || !std::isfinite(*f.latitude) || !std::isfinite(*f.longitude))
    return "the answer does not say which place it is for";
  double dLon = std::fabs(*f.longitude - longitude);
  if (dLon > 180.0) dLon = 360.0 - dLon;  // across the date line
  if (std::fabs(*f.latitude - latitude) > kForecastPlaceToleranceDeg || dLon > kForecastPlaceToleranceDeg) {
    char text[160];
    std::snprintf(text, sizeof text, "the forecast is for another place (%.4f, %.4f) than asked (%.4f, %.4f)",
                  *f.latitude, *f.longitude, latitude, longitude);
    return text;
  }
  const std::int64_t today = unixNowS >= 0 ? unixNowS / 86400 : (unixNowS - 86399) / 86400;
  for (int i = 0; i < f.dayCount; ++i) {
    const auto& text = f.days[static_cast<std::size_t>(i)].date;
    const auto n = dayNumber(text);
    if (!n) return "daily.time holds '" + text + "', not a date";
    // Day 1 is today where the boat is: the UTC date, or one day either side.
    if (i == 0 && (*n < today - 1 || *n > today + 1))
      return "the forecast is for " + text + ", not for today";
    if (i > 0 && *n != *dayNumber(f.days[0].date) + i) return "the forecast's days are not consecutive";
  }
  return "";
}

ForecastParse parseOpenMeteoDaily(std::string_view body) {
  ForecastParse r;
  json::error_code ec;
  const json::value v = json::parse(body, ec);
  if (ec) return {std::nullopt, "not JSON"};
  const auto* root = v.if_object();
  const auto* dailyV = root ? root->if_contains("daily") : nullptr;
  const auto* daily = dailyV ? dailyV->if_object() : nullptr;
  if (!daily) return {std::nullopt, "no daily object"};
  const auto* time = arrayAt(*daily, "time");
  const auto* uv = arrayAt(*daily, "uv_index_max");
  const auto* rad = arrayAt(*daily, "shortwave_radiation_sum");
  if (!time || !uv || !rad)
    return {std::nullopt, "daily lacks time, uv_index_max or shortwave_radiation_sum"};
  if (uv->size() != time->size() || rad->size() != time->size())
    return {std::nullopt, "daily arrays of different lengths"};
  Forecast f;
  for (auto [key, out] : {std::pair{"latitude", &f.latitude}, std::pair{"longitude", &f.longitude}})
    if (const auto* x = root->if_contains(key); x && x->is_number()) *out = x->to_number<double>();
  f.dayCount = static_cast<int>(std::min<std::size_t>(time->size(), f.days.size()));
  for (int i = 0; i < f.dayCount; ++i) {
    const auto k = static_cast<std::size_t>(i);
    auto& d = f.days[k];
    if (const auto* s = (*time)[k].if_string())
      d.date = std::string(*s);
    else
      return {std::nullopt, "daily.time holds a non-string"};
    if (!numberOrNull((*uv)[k], kUvMax, d.uvIndexMax)) return {std::nullopt, "uv_index_max not a UV index"};
    if (!numberOrNull((*rad)[k], kRadiationMaxMJm2, d.radiationMJm2))
      return {std::nullopt, "shortwave_radiation_sum not a daily radiation"};
  }
  r.forecast = f;
  return r;
}

}  // namespace xr::integrations

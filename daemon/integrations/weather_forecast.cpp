#include "integrations/weather_forecast.h"

#include <boost/json.hpp>
#include <cmath>

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

}  // namespace

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

// Where the boat is (see boat_position.h).
#include "integrations/boat_position.h"

#include <boost/json.hpp>
#include <cmath>

namespace xr::integrations {
namespace json = boost::json;

bool usablePosition(double latitudeDeg, double longitudeDeg) {
  return std::isfinite(latitudeDeg) && std::isfinite(longitudeDeg) && std::abs(latitudeDeg) <= 90.0 &&
         std::abs(longitudeDeg) <= 180.0 && !(latitudeDeg == 0.0 && longitudeDeg == 0.0);
}

std::optional<ChosenPosition> choosePosition(const std::vector<PositionReport>& boat, double fileLatitudeDeg,
                                             double fileLongitudeDeg) {
  const PositionReport* best = nullptr;
  for (const auto& r : boat) {
    if (!usablePosition(r.latitudeDeg, r.longitudeDeg) || !(r.ageS >= 0.0 && r.ageS <= kBoatPositionMaxAgeS))
      continue;
    if (!best || r.ageS < best->ageS) best = &r;
  }
  if (best) return ChosenPosition{best->latitudeDeg, best->longitudeDeg, best->source};
  if (usablePosition(fileLatitudeDeg, fileLongitudeDeg))
    return ChosenPosition{fileLatitudeDeg, fileLongitudeDeg, "file"};
  return std::nullopt;
}

bool needsNewForecast(const std::optional<ChosenPosition>& used, const std::optional<ChosenPosition>& now) {
  if (!now) return false;  // nothing better to ask for
  if (!used) return true;
  return std::abs(now->latitudeDeg - used->latitudeDeg) > kForecastMoveDeg ||
         std::abs(now->longitudeDeg - used->longitudeDeg) > kForecastMoveDeg;
}

namespace {
std::optional<double> numberAt(const json::object& o, const char* key) {
  const json::value* v = o.if_contains(key);
  if (!v || !v->is_number()) return std::nullopt;
  return v->to_number<double>();
}
}  // namespace

std::optional<ChosenPosition> positionFromSignalKDelta(const json::value& delta) {
  const json::object* d = delta.if_object();
  const json::value* updates = d ? d->if_contains("updates") : nullptr;
  if (!updates || !updates->is_array()) return std::nullopt;
  std::optional<ChosenPosition> found;
  for (const auto& u : updates->get_array()) {
    const json::value* values = u.is_object() ? u.get_object().if_contains("values") : nullptr;
    if (!values || !values->is_array()) continue;
    for (const auto& pv : values->get_array()) {
      const json::object* o = pv.if_object();
      const json::value* path = o ? o->if_contains("path") : nullptr;
      const json::value* value = o ? o->if_contains("value") : nullptr;
      if (!path || !path->is_string() || path->get_string() != "navigation.position" || !value ||
          !value->is_object())
        continue;
      const auto lat = numberAt(value->get_object(), "latitude");
      const auto lon = numberAt(value->get_object(), "longitude");
      if (lat && lon && usablePosition(*lat, *lon)) found = ChosenPosition{*lat, *lon, "signalk"};
    }
  }
  return found;  // the last one in the delta: the newest
}

void SignalKPosition::post(double latitudeDeg, double longitudeDeg,
                           std::chrono::steady_clock::time_point at) {
  std::lock_guard lock(m_);
  last_ = PositionReport{"signalk", latitudeDeg, longitudeDeg, 0.0};
  at_ = at;
}

std::optional<PositionReport> SignalKPosition::report(std::chrono::steady_clock::time_point now) const {
  std::lock_guard lock(m_);
  if (!last_) return std::nullopt;
  PositionReport r = *last_;
  r.ageS = std::chrono::duration<double>(now - at_).count();
  return r;
}

}  // namespace xr::integrations

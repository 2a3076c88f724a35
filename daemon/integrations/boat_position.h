#pragma once
// Where the boat is, for the weather forecast (docs/integrations.md
// "Weather"): the file's latitude and longitude, or the boat's own position
// from NMEA 2000 (129025 / 129029) or Signal K (navigation.position). A boat
// source less than a day old wins over the file, and of two boat sources
// the one heard last wins. Pure, apart from SignalKPosition's lock.
#include <boost/json/value.hpp>
#include <chrono>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace xr::integrations {

// Older than this, a boat position says less than the owner's file: a
// passage of a day moves the boat out of the forecast's cell anyway.
inline constexpr double kBoatPositionMaxAgeS = 24.0 * 3600.0;
// A move smaller than this keeps the forecast: the grid of a global model
// is ~0.1-0.25 deg, and a boat at anchor swings.
inline constexpr double kForecastMoveDeg = 0.1;

struct PositionReport {
  std::string source;  // "nmea2000", "signalk"
  double latitudeDeg = 0.0, longitudeDeg = 0.0;
  double ageS = 0.0;
};

struct ChosenPosition {
  double latitudeDeg = 0.0, longitudeDeg = 0.0;
  std::string source;  // "nmea2000", "signalk" or "file"
};

// In range, finite, and not (0, 0): the unset default, not a place (a
// forecast for the Gulf of Guinea would rest a Baltic boat's alternator).
bool usablePosition(double latitudeDeg, double longitudeDeg);

// The freshest usable boat report under kBoatPositionMaxAgeS, else the
// file's position when usable, else nullopt (no forecast can be asked for).
std::optional<ChosenPosition> choosePosition(const std::vector<PositionReport>& boat, double fileLatitudeDeg,
                                             double fileLongitudeDeg);

// True when the forecast asked for `used` no longer fits `now`: a position
// appeared, or the boat moved more than kForecastMoveDeg.
bool needsNewForecast(const std::optional<ChosenPosition>& used, const std::optional<ChosenPosition>& now);

// navigation.position from a Signal K delta ({"updates":[{"values":[{"path":
// "navigation.position","value":{"latitude":..,"longitude":..}}]}]});
// nullopt when the delta has none or it is not a usable position.
std::optional<ChosenPosition> positionFromSignalKDelta(const boost::json::value& delta);

// The newest position the Signal K client heard; read by the forecast client.
class SignalKPosition {
 public:
  void post(double latitudeDeg, double longitudeDeg, std::chrono::steady_clock::time_point at);
  std::optional<PositionReport> report(std::chrono::steady_clock::time_point now) const;

 private:
  mutable std::mutex m_;
  std::optional<PositionReport> last_;
  std::chrono::steady_clock::time_point at_{};
};

}  // namespace xr::integrations

#pragma once
// The forecast client (docs/integrations.md "Weather"): on the integrations'
// io_context, never the control thread. Every refresh_min it asks an
// Open-Meteo-compatible server for three days of UV index and radiation,
// decides with decideWeatherMode, and hands the decision to the regulator as
// a weather_mode command: the same path, reason and ramp as one sent by hand.
//
// The position is the boat's own when it has one (NMEA 2000 or Signal K, the
// freshest; boat_position.h), else the file's; a move of more than
// kForecastMoveDeg asks again at once. When it cannot know (no position, a
// server that fails, a forecast older than 24 h) weather mode is off and the
// regulator charges as usual. A failure is logged once per outage with the
// next try; retries are counted.
#include <boost/asio/awaitable.hpp>
#include <boost/asio/io_context.hpp>
#include <chrono>
#include <exception>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <utility>

#include "config/settings.h"
#include "integrations/backoff.h"
#include "integrations/boat_position.h"
#include "integrations/home_assistant.h"
#include "integrations/integration_health.h"
#include "integrations/weather_decision.h"
#include "runtime/handoffs.h"

namespace xr::integrations {

struct HttpUrl {
  std::string host, port, target;  // target: the path
};
// http://host[:port]/path; nullopt when it is not such a URL.
std::optional<HttpUrl> parseHttpUrl(const std::string& url);

// The request's target: path?latitude=..&longitude=..&daily=...&forecast_days=3&timezone=auto.
std::string forecastTarget(const std::string& path, double latitude, double longitude);

// An answer larger than this is not a three-day forecast (a real one is ~600 bytes).
inline constexpr std::size_t kForecastBodyLimit = 64 * 1024;

class WeatherClient {
 public:
  // `signalk`: the Signal K client's navigation.position, or null.
  // `clock`: refreshes, retries, the request's timeout, the forecast's age
  // and today's date run on it (clock_wait.h).
  WeatherClient(boost::asio::io_context& io, const WeatherSettings& s, rt::Handoffs& handoffs,
                CommandSink commands, const rt::WallClock& clock, const SignalKPosition* signalk = nullptr);
  void start();
  void stop();
  // The forecast, the decision and why, in values (uv_day1.., radiation_day1..,
  // active, sunny_days, age_s, latitude, longitude), the position's source
  // in texts (position_source: nmea2000, signalk, file, none); last_error
  // says why not.
  IntegrationStatus status() const;

 private:
  boost::asio::awaitable<void> run();
  boost::asio::awaitable<std::string> fetch(const ChosenPosition& at);
  boost::asio::awaitable<std::pair<std::string, std::exception_ptr>> fetchCaught(const ChosenPosition& at);
  boost::asio::awaitable<std::string> fetchUntimed(const ChosenPosition& at);
  boost::asio::awaitable<void> waitForNextRefresh(std::chrono::steady_clock::duration next);
  std::optional<ChosenPosition> currentPosition() const;
  void report(const std::string& error, WeatherMissing why, int status,
              std::chrono::steady_clock::duration next);
  void decide(std::chrono::steady_clock::time_point now);
  void send(bool active, const std::string& why);
  void publish(const WeatherDecision& d, double ageS);

  boost::asio::io_context& io_;
  WeatherSettings settings_;
  const rt::WallClock& clock_;
  rt::Handoffs& handoffs_;  // reads, and posts events (SideEvents)
  CommandSink commands_;
  const SignalKPosition* signalk_;
  HttpUrl url_;
  IntegrationHealth health_;
  Backoff backoff_;
  bool stopping_ = false;
  std::optional<Forecast> forecast_;
  std::optional<ChosenPosition> asked_;  // the position of the last request, answered or not
  std::chrono::steady_clock::time_point forecastAt_{};
  std::optional<bool> sent_;  // the last state handed to the regulator
  bool outage_ = false;       // a WeatherForecastMissing event stands
  mutable std::mutex m_;      // values_ are read by the web threads
  std::map<std::string, double> values_;
  std::map<std::string, std::string> texts_;
  // For the ages /api/system reports at the moment it is asked (under m_):
  // the forecast's arrival and the last failed fetch (cleared by a success).
  std::optional<std::chrono::steady_clock::time_point> shownForecastAt_, failedAt_;
};

}  // namespace xr::integrations

#include "integrations/weather_client.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <boost/asio/co_spawn.hpp>
#include <boost/asio/detached.hpp>
#include <boost/asio/experimental/awaitable_operators.hpp>
#include <boost/asio/redirect_error.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/use_awaitable.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <cmath>
#include <stdexcept>
#include <variant>

#include "integrations/clock_wait.h"

namespace xr::integrations {
namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
using asio::use_awaitable;
using tcp = asio::ip::tcp;
using namespace std::chrono_literals;
using namespace asio::experimental::awaitable_operators;

namespace {
constexpr auto kIoTimeout = 10s;      // the whole request: connect, write, read
constexpr auto kPositionCheck = 10s;  // between refreshes: did a position appear, did the boat move?
constexpr const char* kSource = "weather forecast";

// A failed refresh, with why in the event's terms.
struct ForecastError : std::runtime_error {
  ForecastError(WeatherMissing w, const std::string& text, int httpStatus = 0)
      : std::runtime_error(text), why(w), status(httpStatus) {}
  WeatherMissing why;
  int status;
};
}  // namespace

std::optional<HttpUrl> parseHttpUrl(const std::string& url) {
  if (!url.starts_with("http://")) return std::nullopt;
  const std::string rest = url.substr(7);
  const auto slash = rest.find('/');
  const std::string hostPort = rest.substr(0, slash);
  HttpUrl u;
  u.target = slash == std::string::npos ? "/" : rest.substr(slash);
  const auto colon = hostPort.rfind(':');
  u.host = colon == std::string::npos ? hostPort : hostPort.substr(0, colon);
  u.port = colon == std::string::npos ? "80" : hostPort.substr(colon + 1);
  if (u.host.empty() || u.port.empty() || u.port.find_first_not_of("0123456789") != std::string::npos ||
      u.target.find('?') != std::string::npos)
    return std::nullopt;
  return u;
}

std::string forecastTarget(const std::string& path, double latitude, double longitude) {
  return fmt::format(
      "{}?latitude={:.4f}&longitude={:.4f}&daily=uv_index_max,shortwave_radiation_sum&forecast_days=3"
      "&timezone=auto",
      path, latitude, longitude);
}

WeatherClient::WeatherClient(asio::io_context& io, const WeatherSettings& s, rt::Handoffs& handoffs,
                             CommandSink commands, const rt::WallClock& clock, const SignalKPosition* signalk)
    : io_(io),
      settings_(s),
      clock_(clock),
      handoffs_(handoffs),
      commands_(std::move(commands)),
      signalk_(signalk),
      health_("weather", clock),
      backoff_(std::chrono::milliseconds(30s), std::chrono::minutes(s.refresh_min)) {
  auto u = parseHttpUrl(s.url);
  if (!u) throw std::runtime_error("weather: url '" + s.url + "' is not http://host[:port]/path");
  url_ = *u;
}

void WeatherClient::start() { asio::co_spawn(io_, run(), asio::detached); }

void WeatherClient::stop() { stopping_ = true; }

asio::awaitable<void> WeatherClient::run() {
  // With no position in the file, give the boat's GPS a moment to be heard
  // before saying there is none (it speaks every second or faster).
  if (!currentPosition()) co_await waitForNextRefresh(kPositionCheck);
  while (!stopping_) {
    health_.attempt();
    std::chrono::steady_clock::duration next = std::chrono::minutes(settings_.refresh_min);
    std::string error;
    WeatherMissing why = WeatherMissing::NoAnswer;
    int status = 0;
    asked_ = currentPosition();
    try {
      if (!asked_)
        throw ForecastError(WeatherMissing::NoPosition,
                            "no position (set latitude and longitude, or a GPS on NMEA 2000 or Signal K)");
      const std::string body = co_await fetch(*asked_);
      auto parsed = parseOpenMeteoDaily(body);
      if (!parsed.forecast)
        throw ForecastError(WeatherMissing::AnswerRefused, "answer refused: " + parsed.error);
      // Today's forecast for the place asked, or none at all.
      const std::int64_t unixNow = clock_.unixMs() / 1000;
      if (const std::string bad =
              forecastMismatch(*parsed.forecast, asked_->latitudeDeg, asked_->longitudeDeg, unixNow);
          !bad.empty())
        throw ForecastError(WeatherMissing::AnswerRefused, "answer refused: " + bad);
      forecast_ = parsed.forecast;
      forecastAt_ = clock_.steadyNow();
      health_.received();
      health_.connected();
      backoff_.reset();
    } catch (const boost::system::system_error& e) {
      error = e.code().message();  // what() carries Beast's source location: not for the user
      if (e.code() == http::error::body_limit) why = WeatherMissing::AnswerRefused;
      next = backoff_.next();
    } catch (const ForecastError& e) {
      error = e.what();
      why = e.why;
      status = e.status;
      next = backoff_.next();
    } catch (const std::exception& e) {
      error = e.what();
      next = backoff_.next();
    }
    if (stopping_) break;
    decide(clock_.steadyNow());
    report(error, why, status, next);
    co_await waitForNextRefresh(next);
  }
}

// Until the next refresh, or sooner when a position appears or the boat
// moved out of the forecast's cell (boat_position.h needsNewForecast).
asio::awaitable<void> WeatherClient::waitForNextRefresh(std::chrono::steady_clock::duration next) {
  const auto due = clock_.steadyNow() + next;
  while (!stopping_) {
    const auto left = due - clock_.steadyNow();
    if (left <= ClockDuration::zero()) break;
    co_await waitOnClock(clock_, std::min<ClockDuration>(left, kPositionCheck), stopping_);
    if (needsNewForecast(asked_, currentPosition())) break;
  }
}

// One log line and one event per outage, with the next try; one event when
// it is back. Retries are counted in /api/system, not logged.
void WeatherClient::report(const std::string& error, WeatherMissing why, int status,
                           std::chrono::steady_clock::duration next) {
  // Events are stamped on the loop's clock, like every other event.
  auto loopNow = [this] { return handoffs_.latest().telemetry.now; };
  {
    std::lock_guard lock(m_);
    if (error.empty())
      failedAt_.reset();
    else
      failedAt_ = clock_.steadyNow();
  }
  if (error.empty()) {
    if (outage_)
      handoffs_.sideEvents.post(makeEvent(loopNow(), EventLevel::Info, EventCode::WeatherForecastBack));
    outage_ = false;
    return;
  }
  const auto s = std::chrono::duration_cast<std::chrono::seconds>(next).count();
  health_.failed(fmt::format("{}: {}; next try in {} s", error,
                             sent_.value_or(false) ? "weather mode holds on the last forecast"
                                                   : "weather mode off, charging as usual",
                             s));
  if (!outage_)
    handoffs_.sideEvents.post(makeEvent(loopNow(), EventLevel::Warning, EventCode::WeatherForecastMissing,
                                        Reason::NONE, static_cast<double>(status), static_cast<double>(s),
                                        static_cast<int>(why)));
  outage_ = true;
}

std::optional<ChosenPosition> WeatherClient::currentPosition() const {
  std::vector<PositionReport> boat;
  const rt::PositionHandoff n2k = handoffs_.n2kPosition.load();
  if (n2k.stamp != 0) {
    // Stamped on the CAN service's clock: its age is on the same clock.
    const TimeNs canNow = handoffs_.canStatus.load().now;
    boat.push_back({"nmea2000", n2k.latitudeDeg, n2k.longitudeDeg, toSec(canNow - n2k.stamp)});
  }
  if (signalk_)
    if (auto r = signalk_->report(clock_.steadyNow())) boat.push_back(*r);
  return choosePosition(boat, settings_.latitude, settings_.longitude);
}

// One deadline for connect, write and read, on the clock: the request that
// loses the race is cancelled. The request's failure is caught and thrown
// again here: `||` waits for a success, so a request that fails must not
// end in an exception, or the failure would wait for the deadline.
asio::awaitable<std::string> WeatherClient::fetch(const ChosenPosition& at) {
  auto r = co_await (fetchCaught(at) || waitOnClock(clock_, kIoTimeout, stopping_));
  if (r.index() == 1)
    throw ForecastError(WeatherMissing::NoAnswer, fmt::format("timeout: no answer within {} s",
                                                              std::chrono::seconds(kIoTimeout).count()));
  auto [body, error] = std::get<0>(std::move(r));
  if (error) std::rethrow_exception(error);
  co_return body;
}

asio::awaitable<std::pair<std::string, std::exception_ptr>> WeatherClient::fetchCaught(
    const ChosenPosition& at) {
  try {
    co_return std::make_pair(co_await fetchUntimed(at), std::exception_ptr{});
  } catch (...) {
    co_return std::make_pair(std::string{}, std::current_exception());
  }
}

asio::awaitable<std::string> WeatherClient::fetchUntimed(const ChosenPosition& at) {
  auto ex = co_await asio::this_coro::executor;
  tcp::resolver resolver(ex);
  const auto hosts = co_await resolver.async_resolve(url_.host, url_.port, use_awaitable);
  beast::tcp_stream stream(ex);
  co_await stream.async_connect(hosts, use_awaitable);
  http::request<http::empty_body> req{http::verb::get,
                                      forecastTarget(url_.target, at.latitudeDeg, at.longitudeDeg), 11};
  req.set(http::field::host, url_.host + ":" + url_.port);
  req.set(http::field::user_agent, "xregulatord");
  req.set(http::field::accept, "application/json");
  co_await http::async_write(stream, req, use_awaitable);
  beast::flat_buffer buf;
  http::response_parser<http::string_body> parser;
  parser.body_limit(kForecastBodyLimit);  // a 10 MB answer is refused, not read
  co_await http::async_read(stream, buf, parser, use_awaitable);
  beast::error_code ec;
  stream.socket().shutdown(tcp::socket::shutdown_both, ec);
  const auto& res = parser.get();
  if (res.result() != http::status::ok)
    throw ForecastError(WeatherMissing::ServerError,
                        "server answered HTTP " + std::to_string(res.result_int()), res.result_int());
  co_return res.body();
}

void WeatherClient::decide(std::chrono::steady_clock::time_point now) {
  const double ageS =
      forecast_ ? std::chrono::duration<double>(now - forecastAt_).count() : kForecastMaxAgeS + 1.0;
  const double threshold = handoffs_.acceptedParams().UVThresholdHigh;
  WeatherDecision d;
  if (forecast_)
    d = decideWeatherMode(*forecast_, threshold, ageS);
  else
    d.why = "no forecast yet: charging as usual";
  publish(d, ageS);
  send(d.active, d.why);
}

void WeatherClient::send(bool active, const std::string& why) {
  if (sent_ == active) return;
  // The regulator starts with weather mode off: the first "off" need not go.
  if (sent_ || active) {
    Command c;
    c.type = CommandType::WeatherMode;
    c.flag = active;
    commands_(c, kSource);
    health_.sent();
  }
  spdlog::info("weather: {}", why);
  sent_ = active;
}

void WeatherClient::publish(const WeatherDecision& d, double ageS) {
  std::map<std::string, double> v;
  for (std::size_t i = 0; i < 3; ++i) {
    const bool have = forecast_ && static_cast<int>(i) < forecast_->dayCount;
    const ForecastDay day = have ? forecast_->days[i] : ForecastDay{};
    v["uv_day" + std::to_string(i + 1)] = day.uvIndexMax.value_or(std::nan(""));
    v["radiation_day" + std::to_string(i + 1)] = day.radiationMJm2.value_or(std::nan(""));
  }
  v["active"] = d.active ? 1.0 : 0.0;
  v["sunny_days"] = d.sunnyDays;
  v["uv_threshold"] = handoffs_.acceptedParams().UVThresholdHigh;
  v["age_s"] = forecast_ ? ageS : std::nan("");
  v["latitude"] = asked_ ? asked_->latitudeDeg : std::nan("");
  v["longitude"] = asked_ ? asked_->longitudeDeg : std::nan("");
  std::lock_guard lock(m_);
  values_ = std::move(v);
  if (forecast_) shownForecastAt_ = forecastAt_;
  texts_["position_source"] = asked_ ? asked_->source : "none";
}

IntegrationStatus WeatherClient::status() const {
  IntegrationStatus s = health_.status();
  std::lock_guard lock(m_);
  s.values = values_;
  s.texts = texts_;
  // Ages now, not at the last decision: the dashboard shows how old the
  // forecast in force is and when a fetch last failed (docs/integrations.md).
  const auto now = clock_.steadyNow();
  if (shownForecastAt_) s.values["age_s"] = std::chrono::duration<double>(now - *shownForecastAt_).count();
  s.values["failed_s_ago"] =
      failedAt_ ? std::chrono::duration<double>(now - *failedAt_).count() : std::nan("");
  return s;
}

}  // namespace xr::integrations

// libFuzzer target for what the network hands the daemon (docs/security.md
// "Untrusted input"): a Venus OS MQTT message (topic + JSON payload), a
// Home Assistant command message, a Signal K delta with a position, and an
// Open-Meteo answer. The first input byte picks the decoder; the rest is the
// message (for MQTT: topic, a 0 byte, payload). Beside the sanitizers'
// findings, each decoder's promise is checked: a Victron value used is
// finite and in its sane range, a refusal says why; a command comes only
// from the exact words; a position is usable; a forecast holds at most three
// days with finite values.
#include <boost/json/src.hpp>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "integrations/boat_position.h"
#include "integrations/ha_discovery.h"
#include "integrations/victron_topics.h"
#include "integrations/weather_forecast.h"

namespace {

using namespace xr::integrations;

void check(bool ok) {
  if (!ok) std::abort();  // a broken promise is a finding, like a sanitizer report
}

void victron(std::string_view topic, std::string_view payload) {
  VictronTopics t;
  t.portalId = "c0619ab1a2b3";
  const auto r = decodeVictron(t, std::string(topic), payload);
  if (!r) return;
  if (!r->refused.empty()) return;  // refused with a reason: nothing used
  if (!r->known) return;
  const VictronRange range = victronRange(r->field);
  check(std::isfinite(r->value) && r->value >= range.lo && r->value <= range.hi);
}

void homeAssistant(std::string_view topic, std::string_view payload) {
  HaTopics t{"homeassistant", "boat1"};
  const HaCommandDecision d = decodeHaCommand(t, topic, payload);
  if (d.command) check(d.refused.empty() && (payload == "off" || payload == "auto" || payload == "PRESS"));
  if (topic != t.modeCommand() && topic != t.limpHomeCommand()) check(!d.command && d.refused.empty());
}

void signalK(std::string_view text) {
  boost::system::error_code ec;
  const boost::json::value v = boost::json::parse(text, ec);
  if (ec) return;
  if (const auto p = positionFromSignalKDelta(v)) check(usablePosition(p->latitudeDeg, p->longitudeDeg));
}

void forecast(std::string_view text) {
  const ForecastParse f = parseOpenMeteoDaily(text);
  check(f.forecast.has_value() != !f.error.empty());
  if (!f.forecast) return;
  check(f.forecast->dayCount >= 0);
  for (const auto& d : f.forecast->days) {
    if (d.uvIndexMax) check(std::isfinite(*d.uvIndexMax));
    if (d.radiationMJm2) check(std::isfinite(*d.radiationMJm2));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const std::string_view all(reinterpret_cast<const char*>(data + 1), size - 1);
  const std::size_t nul = all.find('\0');
  const std::string_view topic = nul == std::string_view::npos ? all : all.substr(0, nul);
  const std::string_view payload = nul == std::string_view::npos ? std::string_view{} : all.substr(nul + 1);
  switch (data[0] % 4) {
    case 0: victron(topic, payload); break;
    case 1: homeAssistant(topic, payload); break;
    case 2: signalK(all); break;
    default: forecast(all); break;
  }
  return 0;
}

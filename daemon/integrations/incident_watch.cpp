#include "integrations/incident_watch.h"

#include <spdlog/spdlog.h>

#include <chrono>

#include "integrations/push_message.h"

namespace xr::integrations {

IncidentWatch::IncidentWatch(boost::asio::io_context& io, IncidentSource source)
    : source_(std::move(source)), timer_(io) {}

void IncidentWatch::hand(const IncidentEdge& e) {
  const IncidentWords w = incidentWords(e);
  spdlog::info("incident {} {}: {}{}", e.incident.id, e.start ? "started" : "ended", w.title,
               e.start ? "" : " (" + w.whatHappened + ")");
  for (auto& l : listeners_) l(e);
}

void IncidentWatch::tick() {
  std::vector<IncidentEdge> edges;
  for (const auto& [event, wallS] : source_.feed->take())
    for (const auto& edge : tracker_.onEvent(event, wallS)) edges.push_back(edge);
  // A protection's trips come in one tick (a warning, then the critical one):
  // the start names the worst of what arrived with it, as the Events row does.
  for (auto& edge : edges) {
    if (edge.start && tracker_.open() && tracker_.open()->id == edge.incident.id)
      edge.incident = *tracker_.open();
    hand(edge);
  }
  if (auto end = tracker_.poll(source_.wallNow())) hand(*end);
  timer_.expires_after(std::chrono::milliseconds(250));
  timer_.async_wait([this](const boost::system::error_code& ec) {
    if (!ec) tick();
  });
}

}  // namespace xr::integrations

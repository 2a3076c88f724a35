#pragma once
// Turns the event feed into incident edges on the integrations' thread
// (docs/integrations.md "Alarms that reach the owner") and hands each edge
// to the integrations that tell the owner: the push and Home Assistant.
// Four times a second it takes the feed's events and asks the tracker
// whether an incident has settled, on the one wall clock (simulated in --sim).
#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <functional>
#include <optional>
#include <vector>

#include "integrations/incident_feed.h"
#include "integrations/incident_tracker.h"

namespace xr::integrations {

// Where the incidents come from: the feed the event pump fills, and the
// wall clock its stamps are on (unix seconds).
struct IncidentSource {
  IncidentFeed* feed = nullptr;
  std::function<double()> wallNow;
};

class IncidentWatch {
 public:
  using Listener = std::function<void(const IncidentEdge&)>;
  IncidentWatch(boost::asio::io_context& io, IncidentSource source);
  void addListener(Listener l) { listeners_.push_back(std::move(l)); }
  void start() { tick(); }
  void stop() { timer_.cancel(); }
  // The incident open now (Home Assistant's state after a reconnect).
  const std::optional<Incident>& open() const { return tracker_.open(); }

 private:
  void tick();
  void hand(const IncidentEdge& e);

  IncidentSource source_;
  IncidentTracker tracker_;
  std::vector<Listener> listeners_;
  boost::asio::steady_timer timer_;
};

}  // namespace xr::integrations

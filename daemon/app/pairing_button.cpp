// The pairing button (pairing_button.h).
#include "app/pairing_button.h"

#include <spdlog/spdlog.h>

#include <array>
#include <string>

#include "app/presence_pairing.h"
#include "app/web_api.h"
#include "web/server/web_server.h"

namespace xr::app {

bool ButtonPress::feed(const ButtonEdge& e) {
  if (e.pressed) {
    if (!down_) {
      down_ = true;
      counted_ = false;
      since_ = e.at;  // a bounce restarts the hold: only an unbroken hold counts
    }
    return false;
  }
  const bool completes = down_ && !counted_ && e.at - since_ >= fromMs(kButtonHoldMs);
  down_ = false;
  return completes;
}

bool ButtonPress::at(TimeNs now) {
  if (!down_ || counted_ || now - since_ < fromMs(kButtonHoldMs)) return false;
  counted_ = true;
  return true;
}

void PairingButtonWatch::poll(ButtonInput* input, TimeNs now, web::WebServer* server, WebApi* api) {
  if (!input) return;
  std::array<ButtonEdge, 16> edges;
  const int n = input->takeEdges(edges);
  if (n < 0) {
    if (!errorLogged_) spdlog::error("pairing button: cannot read its GPIO line; the button is ignored");
    errorLogged_ = true;
    return;
  }
  bool pressed = false;
  for (int i = 0; i < n; ++i) {
    // The held-down test first: a press completed before this release counted already.
    pressed |= press_.at(edges[i].at);
    pressed |= press_.feed(edges[i]);
  }
  pressed |= press_.at(now);
  if (!pressed || !server) return;
  server->openPresencePairingWindow(kPresenceWindowMs);
  if (evented_ && now - lastEvent_ < fromMs(kButtonEventGapMs)) return;
  evented_ = true;
  lastEvent_ = now;
  const std::string text =
      "Pairing window opened for 2 min by the pairing button: one device may pair without a code";
  if (api)
    api->securityEvent(text);
  else
    spdlog::warn("security: {}", text);
}

}  // namespace xr::app

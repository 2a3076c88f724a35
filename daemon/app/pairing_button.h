#pragma once
// The pairing button (docs/security.md "Pairing without a terminal"): a
// press of a push button on [pairing] button_line proves a person on board,
// like the ignition turned off-on-off-on, and opens the same 2-minute window
// in which one phone pairs without a code, with the same event.
//
// ButtonPress is the pure rule on the line's time-stamped edges: a press
// counts once the button has been held down kButtonHoldMs without a break,
// so a contact's bounce or a glitch on a long wire (a few ms) opens nothing;
// holding it down counts once. PairingButtonWatch polls the line from the
// supervisor thread (every 100 ms): the edges keep their own stamps, so the
// polling period does not shorten or lengthen a press.
#include <cstdint>

#include "core/time.h"
#include "drivers/hal/button.h"

namespace xr::web {
class WebServer;
}

namespace xr::app {

class WebApi;

inline constexpr std::int64_t kButtonHoldMs = 50;
// A second press within this time opens the window again but makes no new
// event: a child playing with the button does not bury the event list.
inline constexpr std::int64_t kButtonEventGapMs = 10'000;

class ButtonPress {
 public:
  // One edge; true once when it completes a press (a release after a hold).
  bool feed(const ButtonEdge& e);
  // The time now on the edges' clock; true once when the button has been
  // down long enough (a press still held).
  bool at(TimeNs now);

 private:
  bool down_ = false, counted_ = false;
  TimeNs since_ = 0;
};

class PairingButtonWatch {
 public:
  // input null: no button configured, nothing ever opens. now: the loop's
  // clock (the one the edges are stamped with).
  void poll(ButtonInput* input, TimeNs now, web::WebServer* server, WebApi* api);

 private:
  ButtonPress press_;
  bool errorLogged_ = false;
  bool evented_ = false;
  TimeNs lastEvent_ = 0;
};

}  // namespace xr::app

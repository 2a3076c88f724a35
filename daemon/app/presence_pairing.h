#pragma once
// Pairing by presence (docs/security.md "Pairing without a terminal"): the
// ignition turned off-on-off-on within 10 s proves a person at the helm, and
// opens a 2-minute window in which one phone pairs without a code.
//
// PresenceSequence is the pure rule, fed with the ignition level and an
// elapsed-time clock; PresencePairing polls the control loop's latest sample
// from the supervisor thread (every 100 ms: a key held in a position for less
// than that is not a person's turn of the key anyway).
#include <array>
#include <cstdint>

namespace xr::rt {
class Handoffs;
}
namespace xr::web {
class WebServer;
}

namespace xr::app {

class WebApi;

inline constexpr std::int64_t kPresenceSequenceMs = 10'000;
inline constexpr std::int64_t kPresenceWindowMs = 2 * 60 * 1000;

class PresenceSequence {
 public:
  // True once, at the last "on" of off-on-off-on completed within 10 s.
  bool feed(bool on, std::int64_t elapsedMs);

 private:
  bool known_ = false, last_ = false;
  std::array<std::int64_t, 3> edges_{};  // the last transitions' times, newest last
  int count_ = 0;                        // transitions kept (at most 3)
};

class PresencePairing {
 public:
  void poll(const rt::Handoffs& handoffs, web::WebServer* server, WebApi* api);

 private:
  PresenceSequence sequence_;
};

}  // namespace xr::app

#pragma once
// What the daemon tells the journal at start and stop, apart from its main
// sequence in daemon.cpp: the control loop's figures and the API token hint.
#include <cstdint>
#include <memory>
#include <string>

#include "runtime/handoffs.h"
#include "runtime/loop_stats.h"
#include "store/state_lock.h"
#include "web/server/pairing.h"

namespace xr::app {

// atInfo false: at debug (seen with --log-level debug only).
void logLoopStats(const rt::LoopStatsSummary& s, const rt::RuntimeHealth& h, bool atInfo = true);

// Whether this minute's loop figures go to the journal at info: the first
// minute, then once an hour while healthy, and at once when a count that
// means trouble grew (own overruns, sensor or output errors, dropped events).
// Every other minute they go at debug: the journal says what changed, once
// (docs/operations.md "The journal").
class LoopStatsCadence {
 public:
  static constexpr int kHealthyEveryMin = 60;
  bool atInfo(const rt::LoopStatsSummary& s, const rt::RuntimeHealth& h) noexcept;

 private:
  int minute_ = 0;
  std::uint64_t overrunsOwn_ = 0, sensorErrors_ = 0, outputErrors_ = 0, eventsDropped_ = 0;
};
// Said plainly: "--http :8104" or "0.0.0.0" opens the API to every network
// the boat is on (docs/security.md). Nothing for a single address.
void logEveryInterface(const std::string& listen, unsigned port);
// One daemon per state database (store/state_lock.h): the lock, or nullptr
// with the reason in the journal and on stderr when another daemon holds it.
std::unique_ptr<StateLock> lockStateDatabase(const std::string& dbPath);
// The start-up pairing code: the journal is where the owner (root, adm or
// systemd-journal) finds it; it is short-lived and single use (pairing.h).
void logPairingCode(const web::Pairing::Code& code);
void logTokenHint(bool generated, bool stored, const std::string& token, const std::string& dbPath);

}  // namespace xr::app

namespace xr::app {

// Not set up: once the core has read the bank class from the battery, the
// accepted parameters follow it and the journal says so, once
// (docs/configuration.md "Not set up"). Called with each fresh snapshot.
void followBankClass(rt::Handoffs& handoffs, const Telemetry& t);

}  // namespace xr::app

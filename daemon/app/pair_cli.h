#pragma once
// `xregulatord --pair`: asks the running daemon for a new pairing code
// (POST /api/pair/code on this machine, with the static write token read
// from the configuration or the state database) and prints it. The daemon
// keeps the code; nothing is written to the database from here, so a root
// shell never leaves root-owned files beside the daemon's database.
#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>

#include "app/presence_pairing.h"  // started beside the code, polled by the supervisor

namespace xr::web {
class WebServer;
}

namespace xr::app {

class StoreService;

inline constexpr std::int64_t kFirstStartWindowMs = 15 * 60 * 1000;

// At start, once the web server runs: a pairing code for the journal, and on
// a new regulator (a state database created at this start, nothing paired)
// the first-start window in which the first device pairs without a code
// (docs/security.md "Pairing without a terminal").
void startPairing(web::WebServer& server, const StoreService* store);

// 0 and the code on out, or 1 with the reason on err.
int pairMain(const std::optional<std::string>& configPath, const std::optional<std::string>& stateDb,
             const std::optional<std::string>& http, std::ostream& out, std::ostream& err);

}  // namespace xr::app

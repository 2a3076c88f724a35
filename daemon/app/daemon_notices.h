#pragma once
// What the daemon tells the journal at start and stop, apart from its main
// sequence in daemon.cpp: the control loop's figures and the API token hint.
#include <string>

#include "runtime/handoffs.h"
#include "runtime/loop_stats.h"
#include "web/server/pairing.h"

namespace xr::app {

void logLoopStats(const rt::LoopStatsSummary& s, const rt::RuntimeHealth& h);
// The start-up pairing code: the journal is where the owner (root, adm or
// systemd-journal) finds it; it is short-lived and single use (pairing.h).
void logPairingCode(const web::Pairing::Code& code);
void logTokenHint(bool generated, bool stored, const std::string& token, const std::string& dbPath);

}  // namespace xr::app

#include "app/daemon_notices.h"

#include <spdlog/spdlog.h>

#include <cstdio>

#include "config/setup_pending.h"
#include "config/web_checks.h"
#include "logging/logging.h"
#include "owner/owner_model.h"
#include "web/server/on_board.h"

namespace xr::app {

bool LoopStatsCadence::atInfo(const rt::LoopStatsSummary& s, const rt::RuntimeHealth& h) noexcept {
  const bool worse = s.overrunsOwn > overrunsOwn_ || h.sensorReadErrors > sensorErrors_ ||
                     h.outputWriteErrors > outputErrors_ || h.eventsDropped > eventsDropped_;
  overrunsOwn_ = s.overrunsOwn;
  sensorErrors_ = h.sensorReadErrors;
  outputErrors_ = h.outputWriteErrors;
  eventsDropped_ = h.eventsDropped;
  const bool due = minute_ % kHealthyEveryMin == 0;
  ++minute_;
  return due || worse;
}

void logLoopStats(const rt::LoopStatsSummary& s, const rt::RuntimeHealth& h, bool atInfo) {
  spdlog::log(atInfo ? spdlog::level::info : spdlog::level::debug,
              "control loop: {} ticks, {} overruns ({} own), tick CPU p99/max {:.0f}/{:.0f} us, period error "
              "p50/p99/max {:.0f}/{:.0f}/{:.0f} us, "
              "compute "
              "p50/p99/max {:.0f}/{:.0f}/{:.0f} us, I/O p50/p99/max {:.0f}/{:.0f}/{:.0f} us, "
              "CH1 {:.0f} Hz (CH0 {:.0f}, CH2 {:.0f}, CH3 {:.0f}), INA {:.0f} Hz, "
              "sensor errors {}, output errors {}, events dropped {}",
              s.ticks, s.overruns, s.overrunsOwn, s.tickCpuP99Us, s.tickCpuMaxUs, s.periodErrP50Us,
              s.periodErrP99Us, s.periodErrMaxUs, s.computeP50Us, s.computeP99Us, s.computeMaxUs, s.ioP50Us,
              s.ioP99Us, s.ioMaxUs, s.ch1SampleRateHz, s.adsChannelRateHz[0], s.adsChannelRateHz[2],
              s.adsChannelRateHz[3], s.inaSampleRateHz, h.sensorReadErrors, h.outputWriteErrors,
              h.eventsDropped);
}

void logEveryInterface(const std::string& listen, unsigned port) {
  if (!isEveryInterface(listen)) return;
  spdlog::warn(
      "the web server listens on EVERY network interface ({}): reads are open to the boat's network, "
      "writes "
      "need a paired phone or the token",
      web::hostPortText(listen, port));
}

std::unique_ptr<StateLock> lockStateDatabase(const std::string& dbPath) {
  auto lock = std::make_unique<StateLock>(dbPath);
  if (lock->result() == StateLock::Result::HeldByOther) {
    spdlog::critical("store: {}", lock->message());
    std::fprintf(stderr, "xregulatord: %s\n", lock->message().c_str());
    return nullptr;
  }
  if (lock->result() == StateLock::Result::NoLockFile) spdlog::warn("store: {}", lock->message());
  return lock;
}

void logPairingCode(const web::Pairing::Code& code) {
  spdlog::info(
      "pairing code {} (single use, valid {} min): enter it on the dashboard to let a phone change "
      "settings; a new one: `xregulatord --pair`",
      code.code, web::kCodeLifetimeMs / 60000);
  if (!loggingToJournal()) std::fprintf(stderr, "xregulatord: pairing code: %s\n", code.code.c_str());
}

// The token itself never goes to the journal (any member of systemd-journal
// could read it): a fingerprint to compare with a phone's, and where to read
// the token (docs/security.md).
void logTokenHint(bool generated, bool stored, const std::string& token, const std::string& dbPath) {
  if (!generated) {
    spdlog::info("API write token: from [web] token in the configuration (fingerprint {})",
                 tokenFingerprint(token));
    return;
  }
  if (stored)
    spdlog::info(
        "API write token: generated, kept in the state database (fingerprint {}); read it with "
        "`xregulatord --print-token --state-db {}` as root or the xregulator user",
        tokenFingerprint(token), dbPath);
  else
    spdlog::info("API write token: generated for this run only (fingerprint {})", tokenFingerprint(token));
  // Started from a terminal (`make run`): the operator sees it there. Under
  // systemd stderr is the journal, so nothing is printed.
  if (!loggingToJournal()) std::fprintf(stderr, "xregulatord: API write token: %s\n", token.c_str());
}

}  // namespace xr::app

namespace xr::app {

void followBankClass(rt::Handoffs& handoffs, const Telemetry& t) {
  if (!handoffs.followBankClass(t.setupBank)) return;
  const std::string notice = owner::setupBankNotice(t.setupBank);
  const std::string limits = setupPendingLimitsText(handoffs.acceptedParams());
  if (t.setupBank.fits)
    spdlog::info("not set up: {} Charging within {}", notice, limits);
  else
    spdlog::warn("not set up: {} Charging within {}", notice, limits);
}

}  // namespace xr::app

#include "app/daemon_services.h"

#include "app/integrations_wiring.h"
#include "logging/journal_gate.h"
#include "logging/logging.h"

namespace xr::app {

DaemonServices::DaemonServices(const CliOptions& cli, const StartState& start, const Settings& settings,
                               rt::Handoffs& handoffs, DaemonRig& rig, std::unique_ptr<CsvWriter> csv,
                               std::unique_ptr<std::ofstream> canLog)
    : pump_(handoffs.events), csv_(std::move(csv)), update_(cli.releaseFile, cli.runDir, cli.updateWatch) {
  StoreService* store = start.store.get();
  pump_.addSource(handoffs.sideEvents);  // the CAN thread's events (docs/integrations.md)
  // The journal gets each change once; repeats of a held alarm row stay in the store and the list.
  pump_.addSink([gate = logging::JournalGate{}](const Event& e) mutable {
    if (gate.pass(e)) logEvent(e);
  });
  // Stamped on the one wall clock: a simulated fault of 100 s lists as 100 s.
  pump_.addSink([this, clock = &start.clock](const Event& e) {
    recent_.add(e, static_cast<double>(clock->unixMs()) / 1000.0, describe(e));
  });
  if (store) pump_.addSink([store](const Event& e) { store->appendEvent(e); });
  // Incidents for the owner away (docs/integrations.md "Alarms that reach the owner"), on the same clock.
  pump_.addSink([this, clock = &start.clock](const Event& e) {
    incidents_.post(e, static_cast<double>(clock->unixMs()) / 1000.0);
  });
  pump_.start();
  if (csv_) csv_->start();

  // The boat's network (docs/integrations.md): its own thread, reading the snapshot only.
  integrations_ = startIntegrations(
      settings, handoffs, store, start.clock,
      {&incidents_, [clock = &start.clock] { return static_cast<double>(clock->unixMs()) / 1000.0; }});
  // CAN (docs/integrations.md): on a board the xr-can thread; the sim rig runs its own.
  if (BoardRig* board = rig.board())
    can_ = startCanThread(settings, handoffs, board->loopClock(), std::move(canLog));

  DaemonWebInputs in;
  in.start = &start;
  in.settings = &settings;
  in.handoffs = &handoffs;
  in.recent = &recent_;
  in.integrations = integrationsView(integrations_.get());
  in.w1Root = rig.w1Root(settings);
  in.lastHeartbeatWallMs = &lastHeartbeatWallMs_;
  in.fieldSafeFault = &outputsFault_;
  in.update = &update_;
  web_ = startWeb(cli, in);
}

void DaemonServices::stop() {
  if (web_.server) web_.server->stop();
  pump_.stop();
  if (csv_) csv_->stop();
}

}  // namespace xr::app

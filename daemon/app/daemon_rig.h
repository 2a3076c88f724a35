#pragma once
// The rig the control cycle runs on, the simulator (--sim) or the board,
// behind one face, so Daemon::run wires either the same way. Opened after the
// output files and before anything runs; its devices live until the daemon
// returns (docs/architecture.md "Start-up").
#include <fstream>
#include <functional>
#include <memory>
#include <string>

#include "app/board_rig.h"
#include "app/daemon_start.h"
#include "app/sim_wiring.h"
#include "runtime/cycle_devices.h"
#include "runtime/driver_sensors.h"
#include "runtime/handoffs.h"
#include "runtime/monotonic_clock.h"

namespace xr::app {

class DaemonRig {
 public:
  // Null when a device cannot be set up: the outputs are driven LOW through
  // the fatal guard, and the reason is in the journal and on stderr.
  // `canLog` goes to the simulator's bus; on the board the CAN thread takes it.
  static std::unique_ptr<DaemonRig> open(const StartState& start, const Settings& settings,
                                         const CliOptions& cli, rt::Handoffs& handoffs,
                                         std::unique_ptr<std::ofstream>& canLog);

  rt::CycleDevices devices() { return sim_ ? sim_->devices() : board_->devices(); }
  Clock& loopClock() { return sim_ ? sim_->loopClock() : board_->loopClock(); }
  rt::MonotonicClock& wall() { return sim_ ? sim_->wall() : board_->wall(); }
  // Maps a loop deadline to wall time (the board's loop clock is the wall).
  std::function<TimeNs(TimeNs)> wallDeadlineOf();
  // Starts the fast sensors, saying in the journal which did not answer.
  void startSensors(double bovlVolts);
  // The 1-Wire folder the set-up page lists probes from.
  std::string w1Root(const Settings& settings) const;
  BoardRig* board() { return board_.get(); }
  // [pairing] button_line: the GPIO line, or the simulated one; null: none.
  ButtonInput* pairingButton() { return sim_ ? sim_->pairingButton() : board_->pairingButton(); }

  // The control thread has ended with the field LOW: only now may the
  // watchdog be disarmed, and the --sim-outputs mirror says "stopped".
  void markCleanStop();

 private:
  DaemonRig() = default;
  std::unique_ptr<SimWiring> sim_;
  std::unique_ptr<BoardRig> board_;
};

}  // namespace xr::app

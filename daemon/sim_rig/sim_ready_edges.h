#pragma once
// The simulated board's ADS1115 ALERT/RDY line: edges at the chip model's
// conversion-ready pulses, on virtual time. Waiting for an edge advances the
// world to it (the chip converts; the plant moves on its own grid), so the
// driver's ready-edge pipeline runs exactly as on the board.
#include "drivers/sim/sim_world.h"
#include "runtime/cycle_devices.h"

namespace xr::sim {

class SimReadyEdges final : public rt::ReadyEdgeSource {
 public:
  explicit SimReadyEdges(SimWorld& world) noexcept : world_(world) {}
  int waitEdge(TimeNs deadline, TimeNs* stamp) noexcept override {
    const TimeNs edge = world_.ads().nextReadyEdge();
    if (edge < 0 || edge >= deadline) return 0;  // no pulse due before the deadline
    if (edge <= world_.now()) return -1;         // a pulse in the past: the model is not up to time
    world_.advanceTo(edge);
    *stamp = edge;
    return 1;
  }

 private:
  SimWorld& world_;
};

}  // namespace xr::sim

#pragma once
// A simulated CAN segment: every node attached sees what the others send
// (not its own frames), in order, like a bus with one controller per node.
// Single-threaded: the simulator runs the devices and the daemon's CAN
// service on one thread, so a run stays deterministic.
#include <deque>
#include <memory>
#include <vector>

#include "drivers/hal/can_bus.h"

namespace xr::can {

class SimCanSegment;

class SimCanNode final : public CanBus {
 public:
  bool send(const CanFrame& f) noexcept override;
  // The simulator never blocks: `timeout` is ignored.
  std::optional<CanFrame> receive(std::chrono::milliseconds timeout) noexcept override;
  CanBusStats stats() const noexcept override { return stats_; }
  // Test hook: the segment drops what this node sends (a cut wire).
  void setSilent(bool silent) noexcept { silent_ = silent; }

 private:
  friend class SimCanSegment;
  static constexpr std::size_t kQueueLimit = 1024;  // a node that never reads drops the oldest
  SimCanSegment* segment_ = nullptr;
  std::deque<CanFrame> inbox_;
  CanBusStats stats_;
  bool silent_ = false;
};

class SimCanSegment {
 public:
  SimCanNode& attach();

 private:
  friend class SimCanNode;
  void deliver(const SimCanNode& from, const CanFrame& f);
  std::vector<std::unique_ptr<SimCanNode>> nodes_;
};

}  // namespace xr::can

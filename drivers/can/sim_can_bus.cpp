// The simulated CAN segment (see sim_can_bus.h).
#include "drivers/can/sim_can_bus.h"

namespace xr::can {

bool SimCanNode::send(const CanFrame& f) noexcept {
  if (!segment_) return false;
  ++stats_.tx;
  if (!silent_) segment_->deliver(*this, f);
  return true;
}

std::optional<CanFrame> SimCanNode::receive(std::chrono::milliseconds) noexcept {
  if (inbox_.empty()) return std::nullopt;
  CanFrame f = inbox_.front();
  inbox_.pop_front();
  ++stats_.rx;
  if (f.error) ++stats_.errorFrames;
  return f;
}

SimCanNode& SimCanSegment::attach() {
  nodes_.push_back(std::make_unique<SimCanNode>());
  nodes_.back()->segment_ = this;
  return *nodes_.back();
}

void SimCanSegment::deliver(const SimCanNode& from, const CanFrame& f) {
  for (auto& n : nodes_) {
    if (n.get() == &from) continue;
    if (n->inbox_.size() >= SimCanNode::kQueueLimit) n->inbox_.pop_front();
    n->inbox_.push_back(f);
  }
}

}  // namespace xr::can

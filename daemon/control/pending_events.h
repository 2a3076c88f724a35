#pragma once
// PendingEvents: the events of commands applied between ticks (CommandApplied,
// CommandRejected, TuningCommitted), held until the next step opens its batch.
// A fixed array: the core allocates nothing after construction.
#include <array>
#include <cstddef>

#include "core/events.h"

namespace xr {

class PendingEvents {
 public:
  static constexpr std::size_t kCapacity = 8;
  // Queues one event; beyond kCapacity between two ticks the rest are dropped
  // (commands come from people, a few a second at most). Returns false then.
  bool queue(const Event& e) noexcept;
  // Moves the queued events into the step's batch, oldest first.
  void drainInto(EventBatch& ev) noexcept;
  std::size_t size() const noexcept { return count_; }

 private:
  std::array<Event, kCapacity> events_{};  // the queued events, oldest first
  std::size_t count_ = 0;                  // how many are queued
};

}  // namespace xr

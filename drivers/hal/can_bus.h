#pragma once
// The one frame-level seam every CAN user talks through (the BMS link and
// NMEA 2000). The Linux implementation is a raw AF_CAN socket
// (drivers/can/socketcan_bus); the simulator hands frames between the
// daemon and simulated devices (drivers/can/sim_can_bus); the candump log
// recorder wraps either. Never called on the RT control thread.
#include <array>
#include <chrono>
#include <cstdint>
#include <optional>

namespace xr {

struct CanFrame {
  std::uint32_t id = 0;   // 11-bit (standard) or 29-bit (extended) identifier
  bool extended = false;  // 29-bit identifier (NMEA 2000 / J1939)
  bool error = false;     // an error frame: `id` holds the kernel's CAN_ERR_* class bits
  std::uint8_t dlc = 0;   // data length, 0..8
  std::array<std::uint8_t, 8> data{};
  bool operator==(const CanFrame&) const = default;
};

// Counters a bus keeps (shown by /api/system and the tests).
struct CanBusStats {
  std::uint64_t rx = 0, tx = 0;
  std::uint64_t txErrors = 0;     // send refused (buffer full, bus-off, ...)
  std::uint64_t errorFrames = 0;  // error frames received
  std::uint64_t busOff = 0;       // bus-off events (the backend restarts the link)
};

class CanBus {
 public:
  virtual ~CanBus() = default;
  // Sends one frame. False when it could not be queued (the caller counts it).
  virtual bool send(const CanFrame& f) noexcept = 0;
  // The next received frame, waiting at most `timeout` (0 = poll). Error
  // frames are returned too (error = true) when the bus reports them.
  virtual std::optional<CanFrame> receive(std::chrono::milliseconds timeout) noexcept = 0;
  virtual CanBusStats stats() const noexcept = 0;
};

}  // namespace xr

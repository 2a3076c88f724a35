#pragma once
// VE.Direct text protocol (Victron): blocks of "\r\n<label>\t<value>" fields
// ending with a "Checksum\t<byte>" field; a block is valid when the sum of
// all its bytes (from the first "\r\n" to the checksum byte) is 0 mod 256.
// Bytes of the HEX protocol (lines starting ':') are skipped. Pure,
// incremental (feed any byte slices), no allocation after construction.
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace xr::vedirect {

struct Frame {
  bool hasV = false, hasI = false, hasPPV = false;
  double voltageV = 0.0;  // label V, mV
  double currentA = 0.0;  // label I, mA (+ = into the battery)
  double ppvW = 0.0;      // label PPV, W (panel power)
  bool hasVPV = false;
  double panelV = 0.0;  // label VPV, mV
  bool hasCS = false;
  int chargeState = 0;  // label CS
};

class Parser {
 public:
  static constexpr std::size_t kMaxLabel = 16;
  static constexpr std::size_t kMaxValue = 40;
  static constexpr std::size_t kMaxFields = 40;

  // Feeds bytes; returns the number of complete valid blocks found. For each
  // valid block `onFrame` is called (a plain function pointer + context: no
  // allocation).
  using FrameFn = void (*)(void* ctx, const Frame& f);
  std::size_t feed(std::string_view bytes, FrameFn onFrame, void* ctx) noexcept;
  void reset() noexcept;

  std::uint32_t badChecksums() const noexcept { return badChecksum_; }
  std::uint32_t malformed() const noexcept { return malformed_; }

 private:
  enum class State { Idle, Label, Value, ChecksumByte, Hex };
  void field() noexcept;
  State state_ = State::Idle;
  State beforeHex_ = State::Idle;
  bool synced_ = false;  // a checksum byte has been seen: block boundaries are known
  std::uint8_t sum_ = 0;
  bool inBlock_ = false;
  char label_[kMaxLabel + 1] = {};
  std::size_t labelLen_ = 0;
  char value_[kMaxValue + 1] = {};
  std::size_t valueLen_ = 0;
  std::size_t fields_ = 0;
  bool corrupt_ = false;
  Frame frame_{};
  std::uint32_t good_ = 0, badChecksum_ = 0, malformed_ = 0;
};

}  // namespace xr::vedirect

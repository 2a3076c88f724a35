#include "drivers/vedirect/vedirect_parser.h"

#include <charconv>
#include <cstring>

namespace xr::vedirect {

namespace {
bool parseLong(const char* s, std::size_t n, long* out) {
  if (n == 0) return false;
  const auto [p, ec] = std::from_chars(s, s + n, *out);
  return ec == std::errc() && p == s + n;
}
}  // namespace

void Parser::reset() noexcept {
  state_ = State::Idle;
  beforeHex_ = State::Idle;
  synced_ = false;
  sum_ = 0;
  labelLen_ = valueLen_ = fields_ = 0;
  corrupt_ = false;
  frame_ = Frame{};
}

void Parser::field() noexcept {
  label_[labelLen_] = '\0';
  value_[valueLen_] = '\0';
  if (++fields_ > kMaxFields) corrupt_ = true;
  long v = 0;
  const bool num = parseLong(value_, valueLen_, &v);
  auto is = [&](const char* l) { return std::strcmp(label_, l) == 0; };
  // Units per the VE.Direct text protocol: V/VPV in mV, I in mA, PPV in W.
  if (is("V")) {
    if (!num) corrupt_ = true;
    frame_.hasV = num;
    frame_.voltageV = static_cast<double>(v) / 1000.0;
  } else if (is("I")) {
    if (!num) corrupt_ = true;
    frame_.hasI = num;
    frame_.currentA = static_cast<double>(v) / 1000.0;
  } else if (is("PPV")) {
    if (!num) corrupt_ = true;
    frame_.hasPPV = num;
    frame_.ppvW = static_cast<double>(v);
  } else if (is("VPV")) {
    if (!num) corrupt_ = true;
    frame_.hasVPV = num;
    frame_.panelV = static_cast<double>(v) / 1000.0;
  } else if (is("CS")) {
    if (!num) corrupt_ = true;
    frame_.hasCS = num;
    frame_.chargeState = static_cast<int>(v);
  }
  labelLen_ = valueLen_ = 0;
}

std::size_t Parser::feed(std::string_view bytes, FrameFn onFrame, void* ctx) noexcept {
  std::size_t found = 0;
  for (const char ch : bytes) {
    const auto b = static_cast<std::uint8_t>(ch);
    // HEX-protocol messages (":...\n") may be interleaved anywhere except in
    // the checksum byte and are not part of the text checksum.
    if (state_ == State::Hex) {
      if (b == '\n') state_ = beforeHex_;
      continue;
    }
    if (b == ':' && state_ != State::ChecksumByte) {
      beforeHex_ = state_;
      state_ = State::Hex;
      continue;
    }
    sum_ = static_cast<std::uint8_t>(sum_ + b);
    switch (state_) {
      case State::Idle:
        if (b == '\n') {
          state_ = State::Label;
          labelLen_ = 0;
        }
        break;
      case State::Label:
        if (b == '\t') {
          label_[labelLen_] = '\0';
          state_ = std::strcmp(label_, "Checksum") == 0 ? State::ChecksumByte : State::Value;
          valueLen_ = 0;
        } else if (b == '\r' || b == '\n' || labelLen_ >= kMaxLabel) {
          corrupt_ = true;
          state_ = b == '\n' ? State::Label : State::Idle;
          labelLen_ = 0;
        } else {
          label_[labelLen_++] = static_cast<char>(b);
        }
        break;
      case State::Value:
        if (b == '\r' || b == '\n') {
          field();
          state_ = b == '\n' ? State::Label : State::Idle;
        } else if (valueLen_ >= kMaxValue) {
          corrupt_ = true;  // keep consuming until the line ends
        } else {
          value_[valueLen_++] = static_cast<char>(b);
        }
        break;
      case State::ChecksumByte:
        // `b` was added above: a valid block sums to 0.
        if (synced_) {
          if (corrupt_) {
            ++malformed_;
          } else if (sum_ != 0) {
            ++badChecksum_;
          } else {
            ++good_;
            ++found;
            if (onFrame) onFrame(ctx, frame_);
          }
        }
        synced_ = true;
        sum_ = 0;
        corrupt_ = false;
        fields_ = 0;
        frame_ = Frame{};
        labelLen_ = valueLen_ = 0;
        state_ = State::Idle;
        break;
      case State::Hex:
        break;
    }
  }
  return found;
}

}  // namespace xr::vedirect

#include "store/history_encoding.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace xr::store {

double historyStep(std::string_view series) {
  // Steps finer than a chart on a phone can show: 10 mV, 0.1 A, 0.01 %,
  // 0.1 F, 1 rpm; the limits (+-327 V, +-3 276 A, +-327 %) are far beyond
  // any reading of a 12-48 V system.
  struct Step {
    std::string_view name;
    double step;
  };
  static constexpr Step kSteps[] = {{"ibv_v", 0.01},   {"target_v", 0.01}, {"bcur_a", 0.1}, {"alt_a", 0.1},
                                    {"soc_pct", 0.01}, {"duty_pct", 0.01}, {"temp_f", 0.1}, {"rpm", 1.0}};
  for (const auto& s : kSteps)
    if (s.name == series) return s.step;
  return 0.1;
}

std::vector<std::uint8_t> encodeHistoryRow(std::span<const float> row, double step) {
  std::vector<std::uint8_t> out(kInt16RowBytes);
  for (int i = 0; i < kHistorySlots; ++i) {
    const double v = i < static_cast<int>(row.size()) ? row[i] : NAN;
    std::int16_t q = kEmptySlot;
    if (!std::isnan(v)) q = static_cast<std::int16_t>(std::clamp(std::round(v / step), -32767.0, 32767.0));
    const auto u = static_cast<std::uint16_t>(q);
    out[2 * i] = static_cast<std::uint8_t>(u & 0xff);
    out[2 * i + 1] = static_cast<std::uint8_t>(u >> 8);
  }
  return out;
}

bool decodeHistoryRow(std::span<const std::uint8_t> blob, double step, std::span<float> out) {
  if (out.size() < kHistorySlots) return false;
  if (blob.size() == kFloatRowBytes) {  // a row written before the int16 form
    std::memcpy(out.data(), blob.data(), kFloatRowBytes);
    return true;
  }
  if (blob.size() != kInt16RowBytes) return false;
  for (int i = 0; i < kHistorySlots; ++i) {
    const auto q =
        static_cast<std::int16_t>(static_cast<std::uint16_t>(blob[2 * i] | (blob[2 * i + 1] << 8)));
    out[i] = q == kEmptySlot ? NAN : static_cast<float>(q * step);
  }
  return true;
}

}  // namespace xr::store

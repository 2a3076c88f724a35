#pragma once
// The chart history's row encoding (docs/performance.md "Storage writes"):
// a row holds 60 slots of one series, each an int16 (little-endian) in a
// fixed step per series chosen for the dashboard's display (0.01 V, 0.1 A,
// 0.01 %, 0.1 F, 1 rpm); INT16_MIN marks an empty slot (no sample, or NaN).
// Half the bytes of the float32 rows written before, so half the pages the
// flush writes and the trim frees. Rows in the old float32 form are read as
// they are (told apart by their length): no migration rewrites them.
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace xr::store {

inline constexpr int kHistorySlots = 60;
inline constexpr std::size_t kFloatRowBytes = kHistorySlots * sizeof(float);
inline constexpr std::size_t kInt16RowBytes = kHistorySlots * sizeof(std::int16_t);
inline constexpr std::int16_t kEmptySlot = INT16_MIN;

// The step of one stored count for a series (0.1 for a name not listed).
double historyStep(std::string_view series);
// row: kHistorySlots values (NaN: empty). A value beyond +-32767 steps is
// stored at that limit (the chart shows the limit, not a wrapped number).
std::vector<std::uint8_t> encodeHistoryRow(std::span<const float> row, double step);
// Fills out (kHistorySlots values) from a stored row of either form; false
// (out untouched) for any other length.
bool decodeHistoryRow(std::span<const std::uint8_t> blob, double step, std::span<float> out);

}  // namespace xr::store

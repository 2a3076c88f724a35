#pragma once
// Integer division rounding toward minus infinity: history buckets and UTC
// stamps of times before 1970 (negative milliseconds) land in the bucket that
// contains them, not the one after.
#include <cstdint>

namespace xr::store {

inline std::int64_t floorDiv(std::int64_t a, std::int64_t b) {
  std::int64_t q = a / b;
  if ((a % b != 0) && ((a < 0) != (b < 0))) --q;
  return q;
}

}  // namespace xr::store

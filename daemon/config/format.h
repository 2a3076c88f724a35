#pragma once
// Number formatting shared by error messages, the generated default file and
// persisted values: the shortest decimal text that reads back to the same double.
#include <cstddef>
#include <string>
#include <string_view>

namespace xr {

std::string formatNumber(double v);

// Levenshtein distance, ASCII case-insensitive (closest-name suggestions).
std::size_t editDistance(std::string_view a, std::string_view b);

}  // namespace xr

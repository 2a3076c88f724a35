// Owner-facing text without "nan": a value that was never read is said as
// "no reading" (docs/operations.md "Reading the journal").
#pragma once

#include <string>

namespace xr {

// Replaces each whole-word nan/inf (and the short unit after it) by "no reading".
std::string calmNonFinite(std::string text);

}  // namespace xr

#include "core/calm_text.h"

#include <cstddef>

namespace xr {

namespace {

bool isLetter(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }

}  // namespace

// A value that was never read prints as "nan" (or "inf"): the owner reads
// "no reading" instead, without the unit that followed it ("IBV=nan V" ->
// "IBV=no reading"). Whole words only: "maintenance" keeps its "nan".
std::string calmNonFinite(std::string text) {
  for (const char* word : {"-nan", "nan", "-inf", "inf"}) {
    const std::string w(word);
    for (std::size_t at = text.find(w); at != std::string::npos; at = text.find(w, at)) {
      std::size_t end = at + w.size();
      const bool wordStart = at == 0 || !isLetter(text[at - 1]);
      // "nans": a unit written against the number ("%.0fs") goes with it.
      if (end < text.size() && text[end] == 's' && (end + 1 == text.size() || !isLetter(text[end + 1])))
        ++end;
      if (!wordStart || (end < text.size() && isLetter(text[end]))) {
        at = end;
        continue;
      }
      std::size_t cut = end;  // " V", " RPM", " %": the unit of the missing value goes too
      if (cut + 1 < text.size() && text[cut] == ' ') {
        std::size_t u = cut + 1;
        while (u < text.size() && (isLetter(text[u]) || text[u] == '%') && u - cut <= 3) ++u;
        if (u > cut + 1 && (u == text.size() || !isLetter(text[u]))) cut = u;
      }
      text.replace(at, cut - at, "no reading");
      at += 10;
    }
  }
  return text;
}

}  // namespace xr

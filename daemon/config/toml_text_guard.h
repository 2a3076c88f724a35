#pragma once
// A check of a TOML text before it goes to toml++ (docs/security.md).
// toml++ 3.3.0 (Debian 12) reaches a TOML_UNREACHABLE (undefined behaviour)
// in is_non_ascii_horizontal_whitespace() whenever it asks whether a
// non-ASCII character is whitespace and the code point falls in a block its
// generated table does not cover (U+00A1-U+0499, U+2CEE-U+30E7 but U+3000,
// U+FBF6-U+FEFE). It asks that
//   - of any character outside a string or comment (after a bare key:
//     "capacity_Ɨ = 400", scenario_fuzz's first finding; after a value ...);
//   - in a multi-line basic string, of the character after a backslash and
//     of the first one after a line-ending backslash's whitespace.
// TOML 1.0 allows non-ASCII text only inside strings and comments, so the
// first kind is invalid anyway; the second is valid TOML that nobody writes
// in a regulator's configuration. The loaders refuse both here, at their
// line and column, and toml++ never sees them.
#include <optional>
#include <string_view>

namespace xr {

struct TomlTextProblem {
  int line = 0;    // 1-based
  int column = 0;  // 1-based, in characters (UTF-8 code points)
  std::string_view message;
};

// The first such character; nullopt when there is none. A UTF-8 byte order
// mark at the very start is allowed (toml++ skips it).
std::optional<TomlTextProblem> tomlTextProblem(std::string_view text);

}  // namespace xr

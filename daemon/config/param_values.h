#pragma once
// Params <-> name/value maps for the store (persisted overrides), the web API
// (GET/PATCH /api/params) and scenario [config] overrides. Names are the
// catalogue's; nothing here spells a parameter out by hand.
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "config/config.h"
#include "params/params.h"

namespace xr {

// A scalar (Float/Int/Bool as a number; bools are 0/1) or a whole RPM table.
using ParamValue = std::variant<double, std::vector<double>>;
using ParamMap = std::map<std::string, ParamValue, std::less<>>;

// Every parameter of p, by catalogue name.
ParamMap toParamMap(const Params& p);
// Only the parameters of p that differ from the catalogue defaults (what the
// store persists as user overrides).
ParamMap overridesFromDefaults(const Params& p);

// Check one value against its catalogue entry; empty string when it fits,
// else "value V out of range [lo, hi] unit" / "expected a whole number" / ...
std::string checkParamValue(const ParamSpec& spec, const ParamValue& v);
// Write v into p (v must already pass checkParamValue).
void setParamValue(Params& p, const ParamSpec& spec, const ParamValue& v);
ParamValue getParamValue(const Params& p, const ParamSpec& spec);

struct PatchResult {
  std::optional<Params> params;     // the new whole Params, only when errors is empty
  std::vector<ConfigError> errors;  // every problem: unknown names (with suggestion),
                                    // bad values, then cross-parameter consistency
  bool ok() const { return params.has_value() && errors.empty(); }
};
// Validate a PATCH as a whole against base: either all of it applies or none.
PatchResult validatePatch(const Params& base, const ParamMap& patch);

// Text form for persistence: "14.5", "1", "[0, 50, 50, ...]". Round-trips exactly.
std::string formatParamValue(const ParamValue& v);
std::optional<ParamValue> parseParamValue(std::string_view text);

// The closest catalogue name to an unknown one (edit distance), or empty when
// nothing is reasonably close.
std::string closestParamName(std::string_view unknown);

}  // namespace xr

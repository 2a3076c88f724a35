#pragma once
// Parameter overrides in the store: the TOML file is the base, the database
// holds what the operator changed through the API. Values are stored as text
// (scalars: shortest round-trip decimal; RPM tables: comma-separated).
#include <string>
#include <string_view>
#include <vector>

#include "params/params.h"
#include "store/store.h"

namespace xr {

std::string formatParamValue(const ParamSpec& spec, const Params& p);
// Parses text into p's field; false (p unchanged, *error set) when malformed
// or out of the catalogue's range.
bool parseParamValue(const ParamSpec& spec, std::string_view text, Params& p, std::string* error);

// Saves `current`'s value of `name` as an override, remembering the file's.
StoreStatus saveParamOverride(Store& store, std::string_view name, const Params& fileParams,
                              const Params& current, std::int64_t nowUnixMs);

// fileParams with every stored override applied. Rows that no longer fit
// (unknown name, bad value) are skipped and described in `errors`.
Params applyStoredOverrides(const Params& fileParams, const std::vector<OverrideRow>& rows,
                            std::vector<std::string>& errors);

}  // namespace xr

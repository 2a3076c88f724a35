#include "store/param_overrides.h"

#include <charconv>
#include <cmath>

namespace xr {

namespace {

std::string fmt(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

bool parseDouble(std::string_view s, double& v) {
  while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
  while (!s.empty() && s.back() == ' ') s.remove_suffix(1);
  if (s.empty()) return false;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  return r.ec == std::errc() && r.ptr == s.data() + s.size() && std::isfinite(v);
}

}  // namespace

std::string formatParamValue(const ParamSpec& spec, const Params& p) {
  if (spec.kind != ParamKind::Table) return fmt(spec.get(p, 0));
  std::string out;
  for (std::size_t i = 0; i < RPM_TABLE_SIZE; ++i) {
    if (i) out += ',';
    out += fmt(spec.get(p, i));
  }
  return out;
}

bool parseParamValue(const ParamSpec& spec, std::string_view text, Params& p, std::string* error) {
  auto fail = [&](const std::string& why) {
    if (error) *error = std::string(spec.name) + ": " + why;
    return false;
  };
  if (spec.kind != ParamKind::Table) {
    double v;
    if (!parseDouble(text, v)) return fail("not a number: '" + std::string(text) + "'");
    if (!valueFits(spec, v)) return fail("out of range: " + std::string(text));
    spec.set(p, 0, v);
    return true;
  }
  double vals[RPM_TABLE_SIZE];
  std::size_t n = 0;
  while (true) {
    const auto comma = text.find(',');
    const std::string_view item = text.substr(0, comma);
    if (n >= RPM_TABLE_SIZE) return fail("more than " + std::to_string(RPM_TABLE_SIZE) + " entries");
    if (!parseDouble(item, vals[n])) return fail("not a number: '" + std::string(item) + "'");
    if (!valueFits(spec, vals[n])) return fail("out of range: " + std::string(item));
    ++n;
    if (comma == std::string_view::npos) break;
    text.remove_prefix(comma + 1);
  }
  if (n != RPM_TABLE_SIZE) return fail("needs " + std::to_string(RPM_TABLE_SIZE) + " entries");
  for (std::size_t i = 0; i < n; ++i) spec.set(p, i, vals[i]);
  return true;
}

StoreStatus saveParamOverride(Store& store, std::string_view name, const Params& fileParams,
                              const Params& current, std::int64_t nowUnixMs) {
  const ParamSpec* spec = findParam(name);
  if (!spec) {
    StoreStatus s;
    s.ok = false;
    s.error = "unknown parameter " + std::string(name);
    return s;
  }
  return store.setOverride(name, formatParamValue(*spec, current), formatParamValue(*spec, fileParams),
                           nowUnixMs);
}

Params applyStoredOverrides(const Params& fileParams, const std::vector<OverrideRow>& rows,
                            std::vector<std::string>& errors) {
  Params p = fileParams;
  for (const auto& row : rows) {
    const ParamSpec* spec = findParam(row.name);
    if (!spec) {
      errors.push_back("stored override of unknown parameter " + row.name + " ignored");
      continue;
    }
    std::string err;
    if (!parseParamValue(*spec, row.value, p, &err)) errors.push_back("stored override ignored: " + err);
  }
  return p;
}

}  // namespace xr

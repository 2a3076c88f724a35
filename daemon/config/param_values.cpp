#include "config/param_values.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "config/format.h"

namespace xr {
namespace {

std::string rangeText(const ParamSpec& spec) {
  std::string r = "allowed " + formatNumber(spec.min) + " to " + formatNumber(spec.max);
  if (!spec.unit.empty()) r += " " + std::string(spec.unit);
  return r;
}

std::string checkScalar(const ParamSpec& spec, double v) {
  if (valueFits(spec, v)) return {};
  if (std::isfinite(v) && v >= spec.min && v <= spec.max) {
    if (spec.kind == ParamKind::Bool) return formatNumber(v) + " is not a switch value: allowed 0 or 1 (or true/false)";
    return formatNumber(v) + " is not a whole number: " + rangeText(spec);
  }
  if (spec.kind == ParamKind::Bool) return formatNumber(v) + " is out of range: allowed 0 or 1 (or true/false)";
  return formatNumber(v) + " is out of range: " + rangeText(spec);
}

}  // namespace

ParamValue getParamValue(const Params& p, const ParamSpec& spec) {
  if (spec.kind != ParamKind::Table) return spec.get(p, 0);
  std::vector<double> t(RPM_TABLE_SIZE);
  for (std::size_t i = 0; i < RPM_TABLE_SIZE; ++i) t[i] = spec.get(p, i);
  return t;
}

void setParamValue(Params& p, const ParamSpec& spec, const ParamValue& v) {
  if (spec.kind == ParamKind::Table) {
    const auto& t = std::get<std::vector<double>>(v);
    for (std::size_t i = 0; i < RPM_TABLE_SIZE && i < t.size(); ++i) spec.set(p, i, t[i]);
  } else {
    spec.set(p, 0, std::get<double>(v));
  }
}

ParamMap toParamMap(const Params& p) {
  ParamMap m;
  for (const auto& s : catalogue()) m.emplace(std::string(s.name), getParamValue(p, s));
  return m;
}

ParamMap overridesFromDefaults(const Params& p) {
  const Params defaults;
  ParamMap m;
  for (const auto& s : catalogue()) {
    auto v = getParamValue(p, s);
    if (v != getParamValue(defaults, s)) m.emplace(std::string(s.name), std::move(v));
  }
  return m;
}

std::string checkParamValue(const ParamSpec& spec, const ParamValue& v) {
  if (spec.kind == ParamKind::Table) {
    const auto* t = std::get_if<std::vector<double>>(&v);
    if (!t) return "expected a list of " + std::to_string(RPM_TABLE_SIZE) + " numbers (" + rangeText(spec) + ")";
    if (t->size() != RPM_TABLE_SIZE)
      return "expected " + std::to_string(RPM_TABLE_SIZE) + " values, got " + std::to_string(t->size());
    for (std::size_t i = 0; i < t->size(); ++i) {
      if (!valueFits(spec, (*t)[i]))
        return "element " + std::to_string(i) + " = " + formatNumber((*t)[i]) + " is out of range: " +
               rangeText(spec);
    }
    return {};
  }
  const auto* d = std::get_if<double>(&v);
  if (!d) return "expected a single number (" + rangeText(spec) + "), got a list";
  return checkScalar(spec, *d);
}

PatchResult validatePatch(const Params& base, const ParamMap& patch) {
  PatchResult r;
  Params next = base;
  for (const auto& [name, value] : patch) {
    const ParamSpec* spec = findParam(name);
    if (!spec) {
      ConfigError e{"patch", 0, 0, name, "unknown parameter"};
      if (auto near = closestParamName(name); !near.empty()) e.message += " (did you mean " + near + "?)";
      r.errors.push_back(std::move(e));
      continue;
    }
    if (auto why = checkParamValue(*spec, value); !why.empty()) {
      r.errors.push_back(ConfigError{"patch", 0, 0, name, why});
      continue;
    }
    setParamValue(next, *spec, value);
  }
  for (auto& e : checkConsistency(next, "patch")) r.errors.push_back(std::move(e));
  if (r.errors.empty()) r.params = next;
  return r;
}

std::string formatParamValue(const ParamValue& v) {
  if (const auto* d = std::get_if<double>(&v)) return formatNumber(*d);
  const auto& t = std::get<std::vector<double>>(v);
  std::string s = "[";
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (i) s += ", ";
    s += formatNumber(t[i]);
  }
  return s + "]";
}

std::optional<ParamValue> parseParamValue(std::string_view text) {
  // strtod needs a terminated buffer.
  const std::string buf(text);
  const char* p = buf.c_str();
  auto skipSpace = [&] {
    while (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r') ++p;
  };
  auto number = [&](double& out) {
    skipSpace();
    char* end = nullptr;
    errno = 0;
    out = std::strtod(p, &end);
    if (end == p || errno == ERANGE) return false;
    p = end;
    return true;
  };
  skipSpace();
  if (*p != '[') {
    double d = 0;
    if (!number(d)) return std::nullopt;
    skipSpace();
    if (*p != '\0') return std::nullopt;
    return ParamValue{d};
  }
  ++p;
  std::vector<double> t;
  skipSpace();
  if (*p == ']') {
    ++p;
  } else {
    for (;;) {
      double d = 0;
      if (!number(d)) return std::nullopt;
      t.push_back(d);
      skipSpace();
      if (*p == ',') {
        ++p;
        continue;
      }
      if (*p == ']') {
        ++p;
        break;
      }
      return std::nullopt;
    }
  }
  skipSpace();
  if (*p != '\0') return std::nullopt;
  return ParamValue{std::move(t)};
}

std::string closestParamName(std::string_view unknown) {
  std::string best;
  std::size_t bestD = std::string::npos;
  for (const auto& s : catalogue()) {
    const auto d = editDistance(unknown, s.name);
    if (d < bestD) {
      bestD = d;
      best = std::string(s.name);
    }
  }
  // Only a plausible typo is worth suggesting.
  const std::size_t limit = std::max<std::size_t>(2, unknown.size() / 3);
  return bestD <= limit ? best : std::string{};
}

}  // namespace xr

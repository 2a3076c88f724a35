#include "drivers/sim/scenario_toml.h"

#include <cmath>
#include <optional>
#include <sstream>

namespace xr::sim::scenario_toml {

int lineOf(const toml::node& n) { return int(n.source().begin.line); }
int lineOf(const toml::key& k) { return int(k.source().begin.line); }

double number(const Ctx& c, const toml::key& k, const toml::node& v, double lo, double hi) {
  std::optional<double> d;
  if (v.is_integer() || v.is_floating_point()) d = v.value<double>();
  if (!d) c.fail(lineOf(v), "'" + std::string(k.str()) + "' must be a number");
  if (!std::isfinite(*d) || *d < lo || *d > hi) {
    std::ostringstream m;
    m << "'" << k.str() << "' = " << *d << " is out of range [" << lo << ", " << hi << "]";
    c.fail(lineOf(v), m.str());
  }
  return *d;
}

std::string text(const Ctx& c, const toml::key& k, const toml::node& v) {
  if (!v.is_string()) c.fail(lineOf(v), "'" + std::string(k.str()) + "' must be a string");
  return *v.value<std::string>();
}

const toml::table& tableOf(const Ctx& c, const toml::key& k, const toml::node& v) {
  if (!v.is_table()) c.fail(lineOf(v), "'" + std::string(k.str()) + "' must be a table");
  return *v.as_table();
}

[[noreturn]] void unknownKey(const Ctx& c, const toml::key& k, std::string_view where) {
  c.fail(lineOf(k),
         "unknown key '" + std::string(k.str()) + "'" + (where.empty() ? "" : " in " + std::string(where)));
}

std::vector<double> numbers(const Ctx& c, const toml::key& k, const toml::node& v, double lo, double hi) {
  const toml::array* a = v.as_array();
  if (!a) c.fail(lineOf(v), "'" + std::string(k.str()) + "' must be an array of numbers");
  std::vector<double> out;
  for (const auto& n : *a) out.push_back(number(c, k, n, lo, hi));
  return out;
}

}  // namespace xr::sim::scenario_toml

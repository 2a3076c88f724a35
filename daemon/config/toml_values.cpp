#include "config/toml_values.h"

#include <cmath>

#include "config/format.h"

namespace xr::detail {
namespace {

std::string rangeText(double lo, double hi, std::string_view unit) {
  std::string r = formatNumber(lo) + " to " + formatNumber(hi);
  if (!unit.empty()) r += " " + std::string(unit);
  return r;
}

std::optional<double> numberOf(const toml::node& n) {
  if (const auto* i = n.as_integer()) return static_cast<double>(i->get());
  if (const auto* f = n.as_floating_point()) return f->get();
  return std::nullopt;
}

}  // namespace

std::string describeNode(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::string: return "string \"" + std::string(n.as_string()->get()) + "\"";
    case toml::node_type::integer: return "integer " + std::to_string(n.as_integer()->get());
    case toml::node_type::floating_point: return "number " + formatNumber(n.as_floating_point()->get());
    case toml::node_type::boolean: return n.as_boolean()->get() ? "boolean true" : "boolean false";
    case toml::node_type::array: return "a list";
    case toml::node_type::table: return "a table";
    case toml::node_type::date: return "a date";
    case toml::node_type::time: return "a time";
    case toml::node_type::date_time: return "a date-time";
    case toml::node_type::none: break;
  }
  return "nothing";
}

std::variant<ParamValue, std::string> paramValueFromNode(const ParamSpec& spec, const toml::node& n) {
  const std::string allowed = "allowed " + rangeText(spec.min, spec.max, spec.unit);
  ParamValue v;
  if (!spec.choices.empty()) {
    // A named choice is written by name ("lifepo4"), never by its number.
    const auto* str = n.as_string();
    if (!str) return "expected one of " + std::string(spec.choices) + " (a quoted name), got " + describeNode(n);
    const auto idx = choiceIndex(spec, str->get());
    if (!idx) return "\"" + std::string(str->get()) + "\" is not one of: " + std::string(spec.choices);
    return ParamValue{static_cast<double>(*idx)};
  }
  switch (spec.kind) {
    case ParamKind::Float:
    case ParamKind::Int: {
      auto d = numberOf(n);
      if (!d) return "expected a number (" + allowed + "), got " + describeNode(n);
      v = *d;
      break;
    }
    case ParamKind::Bool: {
      if (const auto* b = n.as_boolean()) v = b->get() ? 1.0 : 0.0;
      else if (auto d = numberOf(n)) v = *d;
      else return "expected true/false or 0/1, got " + describeNode(n);
      break;
    }
    case ParamKind::Table: {
      const auto* arr = n.as_array();
      if (!arr)
        return "expected a list of " + std::to_string(RPM_TABLE_SIZE) + " numbers (" + allowed + "), got " +
               describeNode(n);
      std::vector<double> t;
      for (std::size_t i = 0; i < arr->size(); ++i) {
        auto d = numberOf(*arr->get(i));
        if (!d) return "element " + std::to_string(i) + ": expected a number (" + allowed + "), got " +
                       describeNode(*arr->get(i));
        t.push_back(*d);
      }
      v = std::move(t);
      break;
    }
  }
  if (auto why = checkParamValue(spec, v); !why.empty()) return why;
  return v;
}

std::variant<SettingValue, std::string> settingValueFromNode(const SettingSpec& spec, const toml::node& n) {
  SettingValue v;
  switch (spec.kind) {
    case SettingKind::String:
      if (const auto* s = n.as_string()) v = std::string(s->get());
      else return "expected a string, got " + describeNode(n);
      break;
    case SettingKind::Bool:
      if (const auto* b = n.as_boolean()) v = b->get();
      else return "expected true or false, got " + describeNode(n);
      break;
    case SettingKind::Int:
      if (const auto* i = n.as_integer()) v = i->get();
      else return "expected a whole number (allowed " + rangeText(spec.min, spec.max, spec.unit) + "), got " +
                  describeNode(n);
      break;
    case SettingKind::Float: {
      auto d = numberOf(n);
      if (!d) return "expected a number (allowed " + rangeText(spec.min, spec.max, spec.unit) + "), got " +
                     describeNode(n);
      v = *d;
      break;
    }
    case SettingKind::IntList: {
      const auto* arr = n.as_array();
      if (!arr) return "expected a list of whole numbers, got " + describeNode(n);
      std::vector<std::int64_t> l;
      for (std::size_t i = 0; i < arr->size(); ++i) {
        const auto* e = arr->get(i)->as_integer();
        if (!e) return "element " + std::to_string(i) + ": expected a whole number, got " + describeNode(*arr->get(i));
        l.push_back(e->get());
      }
      v = std::move(l);
      break;
    }
  }
  if (auto why = checkSettingValue(spec, v); !why.empty()) return why;
  return v;
}

}  // namespace xr::detail

// PATCH and GET /api/params: every value is checked against the catalogue
// before any is applied; one bad field rejects the whole patch.
#include <boost/json.hpp>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "params/derived.h"
#include "web/server/api_handler.h"
#include "web/server/api_reply.h"
#include "web/server/json_format.h"

namespace xr::web {

using namespace api;

namespace {

std::string plain(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string rangeText(const ParamSpec& spec) {
  return "must be between " + plain(spec.min) + " and " + plain(spec.max) +
         (spec.unit.empty() ? "" : " " + std::string(spec.unit));
}

// One scalar value for spec, or an error message.
std::optional<double> scalarFor(const ParamSpec& spec, const json::value& v, std::string& err) {
  std::optional<double> d;
  if (!spec.choices.empty() && v.is_string()) {
    // A named choice by name ("agm"), as in the file.
    const auto idx = choiceIndex(spec, std::string_view(v.get_string()));
    if (!idx) {
      err = "expected one of " + std::string(spec.choices);
      return std::nullopt;
    }
    return static_cast<double>(*idx);
  }
  if (spec.kind == ParamKind::Bool && v.is_bool())
    d = v.get_bool() ? 1.0 : 0.0;
  else
    d = jsonNumber(v);
  if (!d) {
    err = spec.kind == ParamKind::Bool ? "expected true/false (or 0/1)" : "expected a number";
    return std::nullopt;
  }
  if (!std::isfinite(*d)) {
    err = "expected a finite number";
    return std::nullopt;
  }
  if ((spec.kind == ParamKind::Int || spec.kind == ParamKind::Bool) && std::trunc(*d) != *d) {
    err = "expected a whole number";
    return std::nullopt;
  }
  if (!valueFits(spec, *d)) {
    err = spec.kind == ParamKind::Bool ? "expected true/false (or 0/1)" : rangeText(spec);
    return std::nullopt;
  }
  return d;
}

// The bank's class (12/24/48 V) as measured (params/derived.h
// bankClassOfVoltage); 0 when no battery voltage is measured.
int measuredClass(double batteryV) {
  if (!std::isfinite(batteryV) || batteryV < 4.5) return 0;
  return nominalVoltage(bankClassOfVoltage(batteryV));
}

// An absolute battery voltage (a set-point or alarm, catalogue minimum 8 V)
// must belong to the measured bank: BulkVoltage = 28.8 on a 12 V bank is
// refused.
std::string voltageClassError(const ParamSpec& spec, double v, int bank) {
  if (!isBankVoltage(spec, v) || bank == 0) return "";
  const int cls = nominalVoltage(bankClassOfVoltage(v));
  if (cls == bank) return "";
  return plain(v) + " V is for a " + std::to_string(cls) + " V battery; this battery measures as a " +
         std::to_string(bank) + " V bank";
}

Response patchErrors(const Request& req, const std::vector<FieldError>& errors) {
  json::object errs;
  for (const auto& e : errors) errs[e.name] = e.message;
  json::object o;
  o["error"] = errors.size() == 1 ? "1 parameter rejected; nothing applied"
                                  : std::to_string(errors.size()) + " parameters rejected; nothing applied";
  o["errors"] = std::move(errs);
  return jsonReply(req, http::status::bad_request, o);
}

}  // namespace

Response ApiHandler::getParams(const Request& req) {
  json::object o =
      paramsToJson(api_.currentParams(), api_.fileParams(), api_.paramSources(), api_.profileOwned());
  // "Default" as the owner means it: the value the battery profile gives
  // where the profile sets the parameter, else the catalogue's
  // (docs/dashboard.md "Settings"). Same catalogue order in both lists.
  const Params eff = api_.effectiveDefaults();
  const json::object effJson = paramsToJson(eff, eff);
  auto& list = o["params"].as_array();
  const auto& effList = effJson.at("params").as_array();
  for (std::size_t i = 0; i < list.size() && i < effList.size(); ++i) {
    auto& p = list[i].as_object();
    p["effective_default"] = p["profile_owned"].as_bool() ? effList[i].as_object().at("value") : p["default"];
  }
  const DaemonApi::SetupState s = api_.setupState();
  o["set_up"] = s.setUp;
  if (!s.setUp) o["setup_limits"] = s.limits;
  return jsonReply(req, http::status::ok, o);
}

Response ApiHandler::patchParams(const Request& req) {
  std::string err;
  auto body = parseBody(req, err);
  if (!body) return error(req, http::status::bad_request, err);
  if (!body->is_object())
    return error(req, http::status::bad_request, "expected a JSON object of parameter name -> value");
  const auto& obj = body->get_object();
  if (obj.empty()) return error(req, http::status::bad_request, "no parameters given");

  std::vector<FieldError> errors;
  std::vector<ParamChange> changes;
  for (const auto& kv : obj) {
    const std::string name(kv.key());
    const ParamSpec* spec = findParam(name);
    if (!spec) {
      errors.push_back({name, "unknown parameter"});
      continue;
    }
    if (kv.value().is_null()) {
      changes.push_back({spec, -1, 0.0, true});  // back to the file / profile / default
      continue;
    }
    if (spec->kind == ParamKind::Table) {
      if (!kv.value().is_array() || kv.value().get_array().size() != RPM_TABLE_SIZE) {
        errors.push_back({name, "expected an array of " + std::to_string(RPM_TABLE_SIZE) + " numbers"});
        continue;
      }
      const auto& arr = kv.value().get_array();
      std::string e;
      for (std::size_t i = 0; i < arr.size() && e.empty(); ++i) {
        auto d = scalarFor(*spec, arr[i], e);
        if (d)
          changes.push_back({spec, static_cast<int>(i), *d});
        else
          e = "element " + std::to_string(i) + ": " + e;
      }
      if (!e.empty()) errors.push_back({name, e});
      continue;
    }
    std::string e;
    if (auto d = scalarFor(*spec, kv.value(), e))
      changes.push_back({spec, -1, *d});
    else
      errors.push_back({name, e});
  }
  if (!errors.empty()) return patchErrors(req, errors);
  StatusSnapshot snap;
  if (api_.latestStatus(snap)) {
    const int bank = measuredClass(snap.telemetry.battery_v);
    for (const auto& c : changes)
      if (c.index < 0 && !c.drop)
        if (auto e = voltageClassError(*c.spec, c.value, bank); !e.empty())
          errors.push_back({std::string(c.spec->name), e});
    if (!errors.empty()) return patchErrors(req, errors);
  }

  PatchResult result = api_.patchParams(changes, writerName(req[http::field::authorization]));
  if (!result.errors.empty()) return patchErrors(req, result.errors);
  json::array applied;
  for (const auto& kv : obj) applied.push_back(json::string(kv.key()));
  json::object o;
  o["ok"] = true;
  o["applied"] = std::move(applied);
  return jsonReply(req, http::status::ok, o);
}

}  // namespace xr::web

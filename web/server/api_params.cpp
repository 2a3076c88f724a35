// PATCH and GET /api/params. The server only PARSES a PATCH: a JSON object
// of known parameter names, each a number, a switch, a named choice or a
// table's array. Every check of the values (the catalogue's ranges, the
// whole set, the bank measured) is the daemon's, once (app/web_api_params.cpp);
// one bad field rejects the whole patch. ?dry_run=1 answers the checked set
// without applying or storing it; ?bank=12|24|48 is the set-up page's bank
// choice, which the daemon turns into values (docs/dashboard.md "Set-up").
#include <boost/json.hpp>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "params/derived.h"
#include "web/server/api_handler.h"
#include "web/server/api_reply.h"
#include "web/server/json_format.h"

namespace xr::web {

using namespace api;

namespace {

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
  return d;
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
  const Params current = api_.currentParams();
  json::object o = paramsToJson(current, api_.fileParams(), api_.paramSources(), api_.profileOwned());
  // The bank these settings are for (params/derived.h, the one rule), so the
  // set-up page shows it without knowing the rule.
  o["bank_v"] = nominalVoltage(systemClass(current));
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

namespace {

// The body as changes (names known, values of the right JSON type), or the
// errors naming each field that is not.
std::vector<ParamChange> parseChanges(const json::object& obj, std::vector<FieldError>& errors) {
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
  return changes;
}

// ?dry_run=1 and ?bank=N; false with *err when the query is malformed.
bool parseOptions(std::string_view target, PatchOptions& opts, std::string& err) {
  const auto q = target.find('?');
  const std::string_view query = q == std::string_view::npos ? std::string_view{} : target.substr(q + 1);
  if (auto dry = queryParam(query, "dry_run")) {
    if (*dry != "1" && *dry != "true" && *dry != "0" && *dry != "false") {
      err = "dry_run: expected 1 or 0";
      return false;
    }
    opts.dryRun = *dry == "1" || *dry == "true";
  }
  if (auto bank = queryParam(query, "bank")) {
    char* end = nullptr;
    const long v = std::strtol(bank->c_str(), &end, 10);
    if (bank->empty() || *end != '\0' || v < 0 || v > 1000) {
      err = "bank: expected the bank's nominal voltage in V (12, 24 or 48)";
      return false;
    }
    opts.bankV = static_cast<int>(v);
  }
  return true;
}

// A dry run's answer: the set as the daemon checked it (every value, by
// name), its bank and the errors; 200 whether or not the set passes.
Response dryRunReply(const Request& req, const PatchResult& result) {
  json::object errs;
  for (const auto& e : result.errors) errs[e.name] = e.message;
  json::object o;
  o["ok"] = result.errors.empty();
  o["dry_run"] = true;
  o["errors"] = std::move(errs);
  if (result.values) {
    json::object values;
    const json::object all = paramsToJson(*result.values, *result.values);  // outlives the loop
    for (const auto& p : all.at("params").as_array()) values[p.at("name").as_string()] = p.at("value");
    o["values"] = std::move(values);
    o["bank_v"] = nominalVoltage(systemClass(*result.values));
  }
  return jsonReply(req, http::status::ok, o);
}

}  // namespace

Response ApiHandler::patchParams(const Request& req) {
  std::string err;
  PatchOptions opts;
  if (!parseOptions(req.target(), opts, err)) return error(req, http::status::bad_request, err);
  auto body = parseBody(req, err);
  if (!body) return error(req, http::status::bad_request, err);
  if (!body->is_object())
    return error(req, http::status::bad_request, "expected a JSON object of parameter name -> value");
  const auto& obj = body->get_object();
  if (obj.empty() && opts.bankV == 0) return error(req, http::status::bad_request, "no parameters given");

  std::vector<FieldError> errors;
  const std::vector<ParamChange> changes = parseChanges(obj, errors);
  if (!errors.empty()) return patchErrors(req, errors);
  PatchResult result = api_.patchParams(changes, writerName(req[http::field::authorization]), opts);
  if (opts.dryRun) return dryRunReply(req, result);
  if (!result.errors.empty()) return patchErrors(req, result.errors);
  json::array applied;
  for (const auto& kv : obj) applied.push_back(json::string(kv.key()));
  json::object o;
  o["ok"] = true;
  o["applied"] = std::move(applied);
  return jsonReply(req, http::status::ok, o);
}

}  // namespace xr::web

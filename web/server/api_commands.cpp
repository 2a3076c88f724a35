// POST and GET /api/commands: one operator command per request, with its
// single argument checked before the daemon sees it; POST /api/dvcc.
#include <array>
#include <boost/json.hpp>
#include <cmath>
#include <string>

#include "web/server/api_handler.h"
#include "web/server/api_reply.h"

namespace xr::web {

using namespace api;

namespace {

constexpr std::array kAllCommands{
    CommandType::Auto,
    CommandType::Manual,
    CommandType::Off,
    CommandType::LimpHome,
    CommandType::LimpHomeOff,
    CommandType::ReenableField,
    CommandType::ResetAlarmLatch,
    CommandType::ResetSocGain,
    CommandType::ResetAltZero,
    CommandType::SetSoc,
    CommandType::SystemIdStart,
    CommandType::TuningCommit,
    CommandType::CvTuningCommit,
    CommandType::WeatherMode,
    CommandType::AcknowledgeAlarm,
};

}  // namespace

Response ApiHandler::postCommand(const Request& req) {
  std::string err;
  auto body = parseBody(req, err);
  if (!body) return error(req, http::status::bad_request, err);
  if (!body->is_object())
    return error(req, http::status::bad_request, "expected a JSON object {\"command\": ...}");
  const auto& obj = body->get_object();
  const auto* name = obj.if_contains("command");
  if (!name || !name->is_string())
    return error(req, http::status::bad_request, "\"command\" must be a string");
  const auto type = parseCommandType(std::string_view(name->get_string()));
  if (!type)
    return error(req, http::status::bad_request, "unknown command '" + std::string(name->get_string()) + "'");
  const std::string_view arg = commandArgument(*type);
  for (const auto& kv : obj)
    if (kv.key() != "command" && kv.key() != arg)
      return error(
          req, http::status::bad_request,
          "unknown field '" + std::string(kv.key()) + "' for command '" + std::string(toString(*type)) + "'");
  Command cmd;
  cmd.type = *type;
  if (!arg.empty()) {
    const auto* v = obj.if_contains(arg);
    if (!v)
      return error(req, http::status::bad_request,
                   "command '" + std::string(toString(*type)) + "' needs '" + std::string(arg) + "'");
    if (arg == "active") {
      if (!v->is_bool()) return error(req, http::status::bad_request, "'active' must be true or false");
      cmd.flag = v->get_bool();
    } else {
      auto d = jsonNumber(*v);
      if (!d || !std::isfinite(*d))
        return error(req, http::status::bad_request, "'" + std::string(arg) + "' must be a number");
      if (*d < 0.0 || *d > 100.0)
        return error(req, http::status::bad_request,
                     "'" + std::string(arg) + "' must be between 0 and 100 %");
      cmd.value = *d;
    }
  }
  CommandResult r = api_.command(cmd);
  json::object o;
  o["ok"] = r.accepted;
  o["command"] = toString(cmd.type);
  o["message"] = r.message;
  if (!r.accepted) o["error"] = r.message.empty() ? "command refused" : r.message;
  return jsonReply(req, r.accepted ? http::status::ok : http::status::conflict, o);
}

// POST /api/dvcc {"charge_voltage_v": V|null, "charge_current_a": A|null}:
// the GX's DVCC limits, relayed by venus/dbus-xregulator. Absent or null =
// the GX did not send that one. The server reads the body; the daemon checks
// the values (core/dvcc_limits.h), applies all or nothing, and tells the
// journal each kind of refusal once, so a body that is not even a number
// goes to the daemon too, as a refusal.
Response ApiHandler::postDvcc(const Request& req) {
  DvccRequest d;
  d.source = writerName(req[http::field::authorization]);
  std::string err;
  auto body = parseBody(req, err);
  if (!body) {
    d.refusal = err;
  } else if (!body->is_object()) {
    d.refusal = "expected a JSON object";
  } else {
    for (const auto& kv : body->get_object()) {
      const bool isV = kv.key() == "charge_voltage_v";
      if (!isV && kv.key() != "charge_current_a") {
        d.refusal = "unknown field '" + std::string(kv.key()) + "'";
        break;
      }
      if (kv.value().is_null()) continue;
      auto n = jsonNumber(kv.value());
      if (!n || !std::isfinite(*n)) {
        d.refusal = "'" + std::string(kv.key()) + "' must be a number or null";
        break;
      }
      (isV ? d.chargeVoltageV : d.chargeCurrentA) = *n;
    }
  }
  CommandResult r = api_.dvccLimits(d);
  json::object o;
  o["ok"] = r.accepted;
  o["message"] = r.message;
  if (!r.accepted) o["error"] = r.message.empty() ? "DVCC limits refused" : r.message;
  return jsonReply(req, r.accepted ? http::status::ok : http::status::bad_request, o);
}

Response ApiHandler::getCommands(const Request& req) {
  json::array a;
  for (auto t : kAllCommands) {
    json::object c;
    c["command"] = toString(t);
    c["argument"] = commandArgument(t);
    a.push_back(std::move(c));
  }
  json::object o;
  o["commands"] = std::move(a);
  return jsonReply(req, http::status::ok, o);
}

}  // namespace xr::web

// GET and PUT /api/setup/hardware: the set-up page's choice of the battery's
// temperature probe and the BMS's CAN interface (docs/configuration.md
// "Set-up"). They are kept by the daemon and run from its next start.
#include <boost/json.hpp>
#include <string_view>
#include <type_traits>

#include "web/server/api_handler.h"
#include "web/server/api_reply.h"

namespace xr::web {

using namespace api;

namespace {

template <class T>
json::object choiceToJson(const HardwareChoice<T>& c) {
  json::object o;
  o["file"] = c.file;
  o["chosen"] = c.chosen ? json::value(*c.chosen) : json::value(nullptr);
  o["running"] = c.running;
  // What the next start will use, and whether that is not what runs now.
  const T next = c.chosen.value_or(c.file);
  o["next"] = next;
  o["restart_needed"] = next != c.running;
  return o;
}

// One field of the body: absent, null, or a value of its kind (a string of
// at most 64 characters, or a number). false: something else.
template <class T>
bool readEdit(const json::object& body, std::string_view key, ChoiceEdit<T>& out) {
  const auto* v = body.if_contains(key);
  if (!v) return true;
  out.touched = true;
  if (v->is_null()) return true;
  if constexpr (std::is_same_v<T, double>) {
    out.value = jsonNumber(*v);
  } else if (v->is_string() && v->get_string().size() <= 64) {
    out.value = std::string(v->get_string());
  }
  return out.value.has_value();
}

}  // namespace

Response ApiHandler::getHardwareSetup(const Request& req) {
  const HardwareSetup h = api_.hardwareSetup();
  json::object o;
  o["savable"] = h.savable;
  o["battery_temp_sensor"] = choiceToJson(h.batteryTempSensor);
  o["bms_interface"] = choiceToJson(h.bmsInterface);
  o["pulley_ratio"] = choiceToJson(h.pulleyRatio);
  o["alternator_sensor"] = h.alternatorSensor;
  o["probes"] = json::value_from(h.probes);
  o["can_interfaces"] = json::value_from(h.canInterfaces);
  o["victron_bms"] = h.victronBms;
  return jsonReply(req, http::status::ok, o);
}

Response ApiHandler::putHardwareSetup(const Request& req) {
  std::string err;
  auto body = parseBody(req, err);
  if (!body) return error(req, http::status::bad_request, err);
  if (!body->is_object()) return error(req, http::status::bad_request, "expected a JSON object");
  const auto& obj = body->get_object();
  for (const auto& kv : obj)
    if (kv.key() != "battery_temp_sensor" && kv.key() != "bms_interface" && kv.key() != "pulley_ratio")
      return error(req, http::status::bad_request, "unknown setting " + std::string(kv.key()));
  HardwareChoiceEdit edit;
  if (!readEdit(obj, "battery_temp_sensor", edit.batteryTempSensor) ||
      !readEdit(obj, "bms_interface", edit.bmsInterface))
    return error(req, http::status::bad_request, "each setting is a string (at most 64 characters) or null");
  if (!readEdit(obj, "pulley_ratio", edit.pulleyRatio))
    return error(req, http::status::bad_request, "pulley_ratio is a number or null");
  if (!edit.batteryTempSensor.touched && !edit.bmsInterface.touched && !edit.pulleyRatio.touched)
    return error(req, http::status::bad_request, "no setting given");
  const auto errors = api_.saveHardwareChoices(edit, writerName(req[http::field::authorization]));
  if (!errors.empty()) {
    json::object errs;
    for (const auto& e : errors) errs[e.name] = e.message;
    json::object o;
    o["error"] = "not saved";
    o["errors"] = std::move(errs);
    return jsonReply(req, http::status::bad_request, o);
  }
  return getHardwareSetup(req);
}

}  // namespace xr::web

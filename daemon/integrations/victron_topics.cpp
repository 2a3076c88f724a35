#include "integrations/victron_topics.h"

#include <boost/json.hpp>
#include <cmath>

namespace xr::integrations {

namespace json = boost::json;

namespace {
constexpr VictronField kAll[] = {VictronField::MaxChargeVoltage, VictronField::MaxChargeCurrent,
                                 VictronField::Soc, VictronField::TemperatureC, VictronField::AllowToCharge};
}  // namespace

const char* toString(VictronField f) {
  switch (f) {
    case VictronField::MaxChargeVoltage:
      return "Info/MaxChargeVoltage";
    case VictronField::MaxChargeCurrent:
      return "Info/MaxChargeCurrent";
    case VictronField::Soc:
      return "Soc";
    case VictronField::TemperatureC:
      return "Dc/0/Temperature";
    case VictronField::AllowToCharge:
      return "Io/AllowToCharge";
  }
  return "?";
}

// Absurd limits are refused, never clamped: a BMS that says 400 V or
// 50 000 A is broken, and its other figures cannot be trusted either.
VictronRange victronRange(VictronField f) {
  switch (f) {
    case VictronField::MaxChargeVoltage:
      return {8.0, 70.0};  // a 12 V bank to a 48 V (16-cell LFP, 58.4 V) bank
    case VictronField::MaxChargeCurrent:
      return {0.0, 2000.0};
    case VictronField::Soc:
      return {0.0, 100.0};
    case VictronField::TemperatureC:
      return {-40.0, 100.0};
    case VictronField::AllowToCharge:
      return {0.0, 1.0};
  }
  return {0.0, 0.0};
}

std::string VictronTopics::topic(VictronField f) const { return prefix() + toString(f); }

std::string VictronTopics::readRequest(VictronField f) const {
  return "R/" + portalId + "/battery/" + std::to_string(batteryInstance) + "/" + toString(f);
}

std::optional<VictronReading> decodeVictron(const VictronTopics& t, const std::string& topic,
                                            std::string_view payload) {
  for (auto f : kAll) {
    if (topic != t.topic(f)) continue;
    VictronReading r;
    r.field = f;
    if (payload.empty()) {
      // dbus-flashmq: "If [a device disappears] a notification will be sent
      // for all topics related to the device. The payload will be empty."
      r.gone = true;
      return r;
    }
    boost::system::error_code ec;
    const json::value v = json::parse(payload, ec);
    if (ec || !v.is_object() || !v.as_object().contains("value")) {
      r.refused = std::string(toString(f)) + ": payload is not {\"value\": ...}";
      return r;
    }
    const json::value& x = v.as_object().at("value");
    if (x.is_null()) return r;  // Venus: the battery has no such value now
    if (!x.is_number()) {
      r.refused = std::string(toString(f)) + ": value is not a number";
      return r;
    }
    const double d = x.to_number<double>();
    const VictronRange range = victronRange(f);
    if (!std::isfinite(d) || d < range.lo || d > range.hi) {
      r.refused = std::string(toString(f)) + ": " + json::serialize(x) + " is outside " +
                  json::serialize(json::value(range.lo)) + " to " + json::serialize(json::value(range.hi));
      return r;
    }
    if (f == VictronField::AllowToCharge && d != 0.0 && d != 1.0) {
      r.refused = "Io/AllowToCharge: must be 0 or 1";
      return r;
    }
    r.known = true;
    r.value = d;
    return r;
  }
  return std::nullopt;
}

}  // namespace xr::integrations

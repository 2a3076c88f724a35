#include "integrations/signalk_delta.h"

#include <boost/json.hpp>
#include <cmath>

#include "core/wall_time_text.h"

namespace xr::integrations {

namespace json = boost::json;

namespace {

constexpr double kZeroCelsiusK = 273.15;

struct PathDef {
  const char* leaf;
  const char* units;  // "" = none (text)
  const char* displayName;
  const char* description;
};

constexpr PathDef kAlternator[] = {
    {"voltage", "V", "Alternator voltage", "Output voltage at the battery sense point"},
    {"current", "A", "Alternator current", "Alternator output current"},
    {"temperature", "K", "Alternator temperature", "Alternator case temperature"},
    {"revolutions", "Hz", "Alternator speed", "Alternator shaft revolutions"},
    {"fieldDrive", "ratio", "Field drive", "Field PWM duty cycle (0-1)"},
    {"chargingMode", "", "Charging mode", "bulk, acceptance, float or other"},
    {"setpointVoltage", "V", "Voltage target", "Charging voltage target"},
    {"setpointCurrent", "A", "Current target", "Alternator current target"},
    {"weatherMode", "", "Weather mode", "1 while weather mode rests the alternator for the sun, else 0"},
    {"runTime", "s", "Alternator running time", "Time the alternator has turned, lifetime"},
    {"insulationLifeUsed", "ratio", "Insulation life used",
     "Share of the windings' insulation life used (0-1)"},
    {"beltSlips", "", "Belt slips", "Belt-slip episodes seen, lifetime"},
    // The owner model's words (docs/dashboard.md "Owner model").
    {"chargingState", "", "Charging state", "What the regulator is doing, in words"},
    {"limitedBy", "", "Limited by", "The most restrictive limit acting now, with its amps, or nothing"},
    {"currentLimit", "A", "Current limit", "The amps of the most restrictive limit acting now"},
};
constexpr PathDef kBattery[] = {
    {"voltage", "V", "Battery voltage", "Battery voltage"},
    {"current", "A", "Battery current", "Battery current, positive charging"},
    {"temperature", "K", "Battery temperature", "Battery temperature"},
    {"capacity.stateOfCharge", "ratio", "State of charge", "State of charge (0-1)"},
    {"capacity.timeRemaining", "s", "Time remaining", "Time to empty at the present discharge"},
    {"capacity.actual", "J", "Measured capacity", "Capacity measured between points of known charge"},
    {"internalResistance", "ohm", "Internal resistance", "DC resistance from load steps, at 25 degC"},
};

}  // namespace

std::vector<SignalKValue> signalKValues(const IntegrationSample& s, const std::string& alternatorId,
                                        const std::string& batteryId) {
  std::vector<SignalKValue> v;
  const std::string alt = "electrical.alternators." + alternatorId + ".";
  const std::string bat = "electrical.batteries." + batteryId + ".";
  auto num = [&](std::string path, double x) {
    if (std::isfinite(x)) v.push_back({std::move(path), x, {}, false});
  };
  num(alt + "voltage", s.battery_v);
  num(alt + "current", s.alt_a);
  num(alt + "temperature", s.alt_temp_c + kZeroCelsiusK);
  num(alt + "revolutions", s.rpm / 60.0);
  num(alt + "fieldDrive", s.field_pct / 100.0);
  v.push_back({alt + "chargingMode", 0.0, std::string(signalKChargingMode(s.stageValue, s.field_on)), true});
  num(alt + "setpointVoltage", s.setpoint_v);
  num(alt + "setpointCurrent", s.setpoint_a);
  num(alt + "weatherMode", s.reason == "REASON_WEATHER_MODE" ? 1.0 : 0.0);
  if (!s.ownerState.empty()) v.push_back({alt + "chargingState", 0.0, s.ownerState, true});
  if (!s.limitedBy.empty()) v.push_back({alt + "limitedBy", 0.0, s.limitedBy, true});
  num(alt + "currentLimit", s.limitAmps);
  num(bat + "voltage", s.battery_v);
  num(bat + "current", s.battery_a);
  if (std::isfinite(s.battery_temp_c)) num(bat + "temperature", s.battery_temp_c + kZeroCelsiusK);
  if (std::isfinite(s.soc_pct)) num(bat + "capacity.stateOfCharge", s.soc_pct / 100.0);
  if (s.time_to_empty_s >= 0) num(bat + "capacity.timeRemaining", s.time_to_empty_s);
  // Signal K's capacities are energies: Ah x the bank's nominal volts x 3600.
  num(bat + "capacity.actual", s.capacity_measured_ah * s.nominal_v * 3600.0);
  num(bat + "internalResistance", s.battery_r_mohm / 1000.0);
  num(alt + "runTime", s.alt_run_hours * 3600.0);
  num(alt + "insulationLifeUsed", s.alt_life_used_pct / 100.0);
  num(alt + "beltSlips", s.belt_slip_events);
  return v;
}

std::vector<SignalKMeta> signalKMeta(const std::string& alternatorId, const std::string& batteryId) {
  std::vector<SignalKMeta> m;
  for (const auto& d : kAlternator)
    m.push_back(
        {"electrical.alternators." + alternatorId + "." + d.leaf, d.units, d.displayName, d.description});
  for (const auto& d : kBattery)
    m.push_back({"electrical.batteries." + batteryId + "." + d.leaf, d.units, d.displayName, d.description});
  return m;
}

std::string signalKDelta(const std::vector<SignalKValue>& values, const std::string& isoTime) {
  json::array vals;
  for (const auto& v : values) {
    json::object o;
    o["path"] = v.path;
    if (v.isText)
      o["value"] = v.text;
    else
      o["value"] = v.number;
    vals.push_back(std::move(o));
  }
  json::object update;
  update["timestamp"] = isoTime;
  update["values"] = std::move(vals);
  json::object d;
  d["context"] = "vessels.self";
  d["updates"] = json::array{std::move(update)};
  return json::serialize(d);
}

std::string signalKMetaDelta(const std::vector<SignalKMeta>& meta) {
  json::array list;
  for (const auto& m : meta) {
    json::object value;
    if (!m.units.empty()) value["units"] = m.units;
    value["displayName"] = m.displayName;
    value["description"] = m.description;
    json::object o;
    o["path"] = m.path;
    o["value"] = std::move(value);
    list.push_back(std::move(o));
  }
  json::object update;
  update["meta"] = std::move(list);
  json::object d;
  d["context"] = "vessels.self";
  d["updates"] = json::array{std::move(update)};
  return json::serialize(d);
}

std::string isoTimeUtc(long long unixMs) {
  const long long ms = ((unixMs % 1000) + 1000) % 1000;
  return wallTimeText(unixMs, "%Y-%m-%dT%H:%M:%S", TimeZone::Utc) + "." +
         std::to_string(1000 + ms).substr(1) + "Z";
}

}  // namespace xr::integrations

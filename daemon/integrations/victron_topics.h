#pragma once
// Venus OS (Victron GX) MQTT topics for a battery's charge limits (docs/integrations.md).
// Venus publishes each D-Bus value as N/<portalId>/<service>/<instance>/<path>
// with a JSON payload {"value": ...} (null when the value is invalid), and
// stops publishing unless R/<portalId>/keepalive is written at least every
// 60 s (dbus-flashmq; Venus OS 2.80+). Pure: topic names and the decoder, so
// the validation is tested without a broker.
#include <optional>
#include <string>
#include <string_view>

namespace xr::integrations {

enum class VictronField { MaxChargeVoltage, MaxChargeCurrent, Soc, TemperatureC, AllowToCharge };

struct VictronTopics {
  std::string portalId;
  int batteryInstance = 512;
  std::string prefix() const { return "N/" + portalId + "/battery/" + std::to_string(batteryInstance) + "/"; }
  std::string keepalive() const { return "R/" + portalId + "/keepalive"; }
  std::string topic(VictronField f) const;
  // A read request: Venus re-reads the D-Bus value and publishes topic(f)
  // again, changed or not. Venus publishes only on change, so this is how a
  // steady limit proves it is still current (dbus-flashmq README, "Read
  // requests").
  std::string readRequest(VictronField f) const;
};

// What one message said: a value to use, "no value" (Venus's null), "the
// device is gone" (Venus's empty payload), or a refusal with its reason (not
// JSON, a string, NaN, out of range).
struct VictronReading {
  VictronField field = VictronField::MaxChargeVoltage;
  bool known = false;  // false: null payload value (the battery has none) or gone
  bool gone = false;   // empty payload: the battery service left the GX's D-Bus
  double value = 0.0;
  std::string refused;  // non-empty: bad input, not used
};

// nullopt when the topic is not one of ours.
std::optional<VictronReading> decodeVictron(const VictronTopics& t, const std::string& topic,
                                            std::string_view payload);

// The sane range of each field; values outside are refused as absurd.
struct VictronRange {
  double lo, hi;
};
VictronRange victronRange(VictronField f);
const char* toString(VictronField f);

}  // namespace xr::integrations

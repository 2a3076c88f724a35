#include "config/integration_checks.h"

#include <cctype>

#include "config/notify_target.h"

namespace xr {

namespace {

bool isTopicId(const std::string& text) {
  if (text.empty() || text.size() > 64) return false;
  for (unsigned char c : text)
    if (!std::isalnum(c) && c != '_' && c != '-') return false;
  return true;
}

// MQTT topic levels must not hold wildcards or separators.
bool isTopicLevels(const std::string& text) {
  if (text.empty()) return false;
  for (char c : text)
    if (c == '+' || c == '#' || c == ' ' || c == '\0') return false;
  return text.front() != '/' && text.back() != '/';
}

}  // namespace

bool isAlphanumericId(const std::string& text) {
  if (text.empty() || text.size() > 64) return false;
  for (unsigned char c : text)
    if (!std::isalnum(c)) return false;
  return true;
}

std::vector<std::pair<std::string, std::string>> checkIntegrations(const IntegrationsSettings& s,
                                                                   const CanSettings& can) {
  std::vector<std::pair<std::string, std::string>> out;
  auto bad = [&](std::string key, std::string msg) { out.emplace_back(std::move(key), std::move(msg)); };

  const auto& k = s.signalk;
  // wss:// is not supported yet (docs/integrations.md): on a boat the server
  // is normally on the local network.
  if (!k.url.starts_with("ws://") || k.url.size() <= 5 || k.url[5] == '/' || k.url[5] == ':')
    bad("integrations.signalk.url",
        "'" + k.url + "' must be ws://host[:port]/path (wss:// is not supported yet)");
  if (!isAlphanumericId(k.alternator_id))
    bad("integrations.signalk.alternator_id", "'" + k.alternator_id + "' must be letters and digits only");
  if (!isAlphanumericId(k.battery_id))
    bad("integrations.signalk.battery_id", "'" + k.battery_id + "' must be letters and digits only");

  const auto& m = s.mqtt;
  if (m.enabled && m.host.empty()) bad("integrations.mqtt.host", "must name the broker when enabled");
  if (!isTopicId(m.node_id))
    bad("integrations.mqtt.node_id", "'" + m.node_id + "' must be letters, digits, _ or - (at most 64)");
  if (!isTopicLevels(m.discovery_prefix))
    bad("integrations.mqtt.discovery_prefix", "'" + m.discovery_prefix + "' is not a usable topic prefix");
  // Commands change what the regulator does: never from an anonymous broker.
  if (m.commands_enabled && (m.username.empty() || m.password.empty()))
    bad("integrations.mqtt.commands_enabled",
        "needs username and password: commands are never taken anonymously");
  if (!m.password.empty() && m.username.empty())
    bad("integrations.mqtt.password", "a password needs a username");

  const auto& v = s.victron;
  if (v.enabled && v.host.empty()) bad("integrations.victron.host", "must name the GX when enabled");
  if (v.enabled && !isTopicId(v.portal_id))
    bad("integrations.victron.portal_id",
        "'" + v.portal_id + "' is not a VRM portal id (letters and digits)");
  // The control law follows one BMS (Handoffs::bms has one writer). Two
  // sources would overwrite each other's limits and hide each other's
  // silence, so the choice is the user's, made here.
  if (v.enabled && !can.bms_interface.empty())
    bad("integrations.victron.enabled",
        "a BMS on CAN ([can] bms_interface = \"" + can.bms_interface +
            "\") already gives the battery limits: use one source (the GX relays the same BMS)");

  // https:// is not supported yet (docs/integrations.md "Weather"): a boat
  // reaches the public service through a local proxy or cache.
  const auto& w = s.weather;
  if (!w.url.starts_with("http://") || w.url.size() <= 7 || w.url[7] == '/' || w.url[7] == ':')
    bad("integrations.weather.url",
        "'" + w.url + "' must be http://host[:port]/path (https:// is not supported yet)");

  // [notify]: a URL the sender could not use is refused at start, with why.
  const auto& n = s.notify;
  std::string why;
  if (!n.url.empty() && !parseNotifyUrl(n.url, &why)) bad("notify.url", "'" + n.url + "' " + why);
  if (!n.header.empty() && !parseNotifyHeader(n.header, &why)) bad("notify.header", why);
  if (n.header.empty() && n.url.empty()) return out;
  if (n.url.empty()) bad("notify.url", "is empty, so the header would go nowhere");
  return out;
}

std::vector<std::pair<std::string, std::string>> checkCan(const CanSettings& s) {
  std::vector<std::pair<std::string, std::string>> out;
  // A CAN interface name (docs/configuration.md "CAN interface names"): the
  // kernel's rule (dev_valid_name: at most 15 bytes, IFNAMSIZ - 1, not "."
  // or "..", no '/', ':' or white space), narrowed to the letters, digits,
  // '-', '_' and '.' that CAN drivers and udev use (can0, vcan0, slcan0,
  // can-house), so markup or shell characters never reach a log, a page or a
  // socket call; and never the loopback "lo", which is no CAN bus.
  auto badName = [](const std::string& n) {
    if (n.empty()) return false;  // none
    if (n.size() > 15 || n == "." || n == ".." || n == "lo") return true;
    for (unsigned char c : n)
      if (!std::isalnum(c) && c != '-' && c != '_' && c != '.') return true;
    return false;
  };
  for (const auto& [key, name] :
       {std::pair<const char*, const std::string&>{"can.bms_interface", s.bms_interface},
        std::pair<const char*, const std::string&>{"can.n2k_interface", s.n2k_interface}})
    if (badName(name))
      out.emplace_back(key, "'" + name +
                                "' is not a CAN interface name (e.g. can0): at most 15 letters, digits, '-', "
                                "'_' or '.', not '.', '..' or 'lo'");
  if (!s.bms_interface.empty() && s.bms_interface == s.n2k_interface)
    out.emplace_back("can.n2k_interface", "must not be the BMS bus: the two run at different bit rates");
  if (s.RpmSource == "n2k" && s.n2k_interface.empty())
    out.emplace_back("can.RpmSource", "n2k needs [can] n2k_interface, the bus the engine speed comes from");
  return out;
}

const char* retiredSetting(const std::string& dottedKey) {
  if (dottedKey == "integrations.victron.stale_s")
    return "no longer a setting: the Victron limits go stale after the BmsStaleS parameter (under [can]), "
           "as a BMS on CAN does";
  return nullptr;
}

}  // namespace xr

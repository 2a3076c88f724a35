// Paired devices in the state database (store_auth.h).
#include "app/store_auth.h"

#include <charconv>

namespace xr::app {

namespace {
constexpr std::string_view kPrefix = "device:";
}

std::optional<web::PairedDevice> parseDeviceRow(std::string_view key, std::string_view value) {
  if (!key.starts_with(kPrefix)) return std::nullopt;
  web::PairedDevice d;
  d.id = std::string(key.substr(kPrefix.size()));
  const auto sp1 = value.find(' ');
  if (sp1 != 64 || d.id.size() != 8) return std::nullopt;
  d.hash = std::string(value.substr(0, sp1));
  if (d.hash.find_first_not_of("0123456789abcdef") != std::string::npos || !d.hash.starts_with(d.id))
    return std::nullopt;
  const auto rest = value.substr(sp1 + 1);
  const auto sp2 = rest.find(' ');
  const auto ms = rest.substr(0, sp2);
  const auto [p, ec] = std::from_chars(ms.data(), ms.data() + ms.size(), d.createdMs);
  if (ec != std::errc{} || p != ms.data() + ms.size()) return std::nullopt;
  d.name = web::cleanDeviceName(sp2 == std::string_view::npos ? std::string_view{} : rest.substr(sp2 + 1));
  return d;
}

std::vector<web::PairedDevice> StoreAuthStore::loadDevices() {
  std::vector<web::PairedDevice> out;
  for (const auto& [k, v] : store_.documents(kPrefix))
    if (auto d = parseDeviceRow(k, v)) out.push_back(std::move(*d));
  return out;
}

bool StoreAuthStore::saveDevice(const web::PairedDevice& d) {
  return store_.putDocument(std::string(kPrefix) + d.id,
                            d.hash + " " + std::to_string(d.createdMs) + " " + d.name);
}

bool StoreAuthStore::removeDevice(const std::string& id) {
  return store_.eraseDocument(std::string(kPrefix) + id);
}

}  // namespace xr::app

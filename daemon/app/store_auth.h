#pragma once
// The paired devices (web/server/pairing.h) in the state database: one kv row
// per device, "device:<id>" = "<sha256 of the token> <created ms> <name>".
// Only the hash is stored, so the database alone gives no write access.
#include "app/store_service.h"
#include "web/server/pairing.h"

namespace xr::app {

class StoreAuthStore final : public web::AuthStore {
 public:
  explicit StoreAuthStore(StoreService& store) : store_(store) {}
  std::vector<web::PairedDevice> loadDevices() override;
  bool saveDevice(const web::PairedDevice& d) override;
  bool removeDevice(const std::string& id) override;

 private:
  StoreService& store_;
};

// Parses one stored row; nullopt for a damaged one (skipped, never trusted).
std::optional<web::PairedDevice> parseDeviceRow(std::string_view key, std::string_view value);

}  // namespace xr::app

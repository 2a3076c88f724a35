// The owner model and durable revocations (docs/security.md "Owner and
// devices"): the installer token and the first paired device revoke any
// device, another device only itself; a revocation the store cannot save is
// refused and changes nothing; each pairing and revocation is a security
// event naming the device.
#include <gtest/gtest.h>

#include <boost/json.hpp>

#include "tests/web/fake_daemon_api.h"
#include "tests/web/http_client.h"
#include "web/server/pairing.h"
#include "web/server/web_server.h"

namespace xr::web::test {
namespace {
namespace json = boost::json;

// A state database that can go read-only: saves and removals then fail.
class FlakyAuthStore final : public AuthStore {
 public:
  std::vector<PairedDevice> loadDevices() override { return inner_.loadDevices(); }
  bool saveDevice(const PairedDevice& d) override { return !readOnly && inner_.saveDevice(d); }
  bool removeDevice(const std::string& id) override {
    if (readOnly || removalsLeft == 0) return false;
    if (removalsLeft > 0) --removalsLeft;
    return inner_.removeDevice(id);
  }
  bool readOnly = false;
  int removalsLeft = -1;  // -1: no limit

 private:
  MemoryAuthStore inner_;
};

struct OwnerFixture : ::testing::Test {
  std::int64_t nowMs = 1'700'000'000'000;
  std::shared_ptr<FlakyAuthStore> store = std::make_shared<FlakyAuthStore>();
  Pairing pairing{store, [this] { return nowMs; }};
  Pairing::Outcome pairOne(const std::string& name) {
    nowMs += 1000;
    return pairing.pair(pairing.newCode().code, name);
  }
  static Pairing::Caller as(const Pairing::Outcome& o) { return {false, o.device.id}; }
};

TEST_F(OwnerFixture, TheFirstPairedDeviceIsTheOwner) {
  const auto owner = pairOne("owner"), guest = pairOne("guest");
  EXPECT_EQ(pairing.ownerId(), owner.device.id);
  EXPECT_TRUE(pairing.isOwner(as(owner)));
  EXPECT_FALSE(pairing.isOwner(as(guest)));
  EXPECT_TRUE(pairing.isOwner({true, ""}));  // the installer token
}

TEST_F(OwnerFixture, AGuestCannotRevokeTheOwnerOrAnotherGuest) {
  const auto owner = pairOne("owner"), guest = pairOne("guest"), other = pairOne("other");
  EXPECT_EQ(pairing.revoke(owner.device.id, as(guest)), Pairing::Revoke::NotAllowed);
  EXPECT_EQ(pairing.revoke(other.device.id, as(guest)), Pairing::Revoke::NotAllowed);
  EXPECT_EQ(pairing.revokeAll(as(guest)).result, Pairing::Revoke::NotAllowed);
  EXPECT_EQ(pairing.devices().size(), 3u);
  EXPECT_TRUE(pairing.isDeviceToken(owner.token));
}

TEST_F(OwnerFixture, ADeviceMayRevokeItselfAndTheOwnerAnyone) {
  const auto owner = pairOne("owner"), guest = pairOne("guest"), other = pairOne("other");
  EXPECT_EQ(pairing.revoke(guest.device.id, as(guest)), Pairing::Revoke::Revoked);
  EXPECT_EQ(pairing.revoke(other.device.id, as(owner)), Pairing::Revoke::Revoked);
  EXPECT_EQ(pairing.devices().size(), 1u);
}

TEST_F(OwnerFixture, OwnershipPassesToTheOldestDeviceLeft) {
  const auto owner = pairOne("owner"), second = pairOne("second");
  pairOne("third");
  ASSERT_EQ(pairing.revoke(owner.device.id, as(owner)), Pairing::Revoke::Revoked);
  EXPECT_EQ(pairing.ownerId(), second.device.id);
}

TEST_F(OwnerFixture, ARevocationThatCannotBeSavedIsRefusedAndTheTokenStillWorks) {
  const auto owner = pairOne("owner"), guest = pairOne("guest");
  store->readOnly = true;
  EXPECT_EQ(pairing.revoke(guest.device.id, as(owner)), Pairing::Revoke::NotSaved);
  EXPECT_TRUE(pairing.isDeviceToken(guest.token));  // memory agrees with the disk
  Pairing restarted{store, [this] { return nowMs; }};
  EXPECT_TRUE(restarted.isDeviceToken(guest.token));
  store->readOnly = false;
  EXPECT_EQ(pairing.revoke(guest.device.id, as(owner)), Pairing::Revoke::Revoked);
  Pairing again{store, [this] { return nowMs; }};
  EXPECT_FALSE(again.isDeviceToken(guest.token));  // success means durable
}

TEST_F(OwnerFixture, ARevokeAllSavedOnlyInPartKeepsMemoryEqualToTheDisk) {
  pairOne("a");
  pairOne("b");
  pairOne("c");
  store->removalsLeft = 1;
  const auto r = pairing.revokeAll({true, ""});
  EXPECT_EQ(r.result, Pairing::Revoke::NotSaved);
  EXPECT_EQ(r.revoked, 1u);
  EXPECT_EQ(pairing.devices().size(), 2u);
  EXPECT_EQ(store->loadDevices().size(), 2u);
}

TEST_F(OwnerFixture, APairingThatCannotBeSavedIsRefused) {
  store->readOnly = true;
  const auto code = pairing.newCode().code;
  EXPECT_EQ(pairing.pair(code, "phone").kind, Pairing::Outcome::NotSaved);
  EXPECT_TRUE(pairing.devices().empty());
}

// ---------------------------------------------------------------- server

class OwnerServerTest : public ::testing::Test {
 protected:
  static constexpr const char* kToken = "installer-token-0123456789abcdef";
  void SetUp() override {
    opts_.listen = "127.0.0.1";
    opts_.port = 0;
    opts_.token = kToken;
    opts_.auth_store = store_;
    server_ = std::make_unique<WebServer>(api_, opts_);
    server_->start();
  }
  HttpResult del(const std::string& target, const std::string& token) {
    return httpRequest(server_->port(), bhttp::verb::delete_, target, "",
                       {{"Authorization", "Bearer " + token}});
  }
  // {token, id}
  std::pair<std::string, std::string> pair(const std::string& name) {
    const auto code = server_->newPairingCode().code;
    const auto r = httpRequest(server_->port(), bhttp::verb::post, "/api/pair",
                               R"({"code": ")" + code + R"(", "name": ")" + name + "\"}");
    EXPECT_EQ(r.status, 200) << r.body;
    const auto j = json::parse(r.body);
    return {std::string(j.at("token").as_string()), std::string(j.at("id").as_string())};
  }
  bool writes(const std::string& token) {
    return httpRequest(server_->port(), bhttp::verb::patch, "/api/params", R"({"BulkVoltage": 14.3})",
                       {{"Authorization", "Bearer " + token}})
               .status == 200;
  }

  FakeDaemonApi api_;
  std::shared_ptr<FlakyAuthStore> store_ = std::make_shared<FlakyAuthStore>();
  WebServerOptions opts_;
  std::unique_ptr<WebServer> server_;
};

TEST_F(OwnerServerTest, ARevocationThatCannotBeSavedAnswers503AndChangesNothing) {
  const auto [ownerToken, ownerId] = pair("owner");
  const auto [guestToken, guestId] = pair("guest");
  store_->readOnly = true;
  const auto r = del("/api/pair/devices/" + guestId, ownerToken);
  EXPECT_EQ(r.status, 503) << r.body;
  EXPECT_NE(r.body.find("cannot be saved"), std::string::npos) << r.body;
  EXPECT_TRUE(writes(guestToken));
  EXPECT_EQ(del("/api/pair/devices", kToken).status, 503);
  EXPECT_TRUE(writes(guestToken));
  EXPECT_TRUE(writes(ownerToken));
}

TEST_F(OwnerServerTest, AGuestPhoneCannotRevokeTheOwner) {
  const auto [ownerToken, ownerId] = pair("owner");
  const auto [guestToken, guestId] = pair("guest");
  EXPECT_EQ(del("/api/pair/devices/" + ownerId, guestToken).status, 403);
  EXPECT_EQ(del("/api/pair/devices", guestToken).status, 403);
  EXPECT_TRUE(writes(ownerToken));
  EXPECT_EQ(del("/api/pair/devices/" + guestId, guestToken).status, 200);  // itself
  EXPECT_FALSE(writes(guestToken));
}

TEST_F(OwnerServerTest, PairingAndRevokingAreSecurityEventsNamingTheDevice) {
  const auto [ownerToken, ownerId] = pair("Skipper phone");
  const auto [guestToken, guestId] = pair("Crew tablet");
  ASSERT_EQ(del("/api/pair/devices/" + guestId, ownerToken).status, 200);
  const auto ev = api_.securityEvents();
  ASSERT_EQ(ev.size(), 3u);
  EXPECT_NE(ev[0].find("Paired device \"Skipper phone\" (" + ownerId + ") as the owner"), std::string::npos)
      << ev[0];
  EXPECT_NE(ev[1].find("Paired device \"Crew tablet\""), std::string::npos) << ev[1];
  EXPECT_EQ(ev[1].find("owner"), std::string::npos) << ev[1];
  EXPECT_NE(ev[2].find("Revoked device \"Crew tablet\" (" + guestId + ") by device \"Skipper phone\""),
            std::string::npos)
      << ev[2];
}

TEST_F(OwnerServerTest, TheDeviceListSaysWhoIsTheOwner) {
  const auto [ownerToken, ownerId] = pair("owner");
  const auto [guestToken, guestId] = pair("guest");
  const auto r = httpRequest(server_->port(), bhttp::verb::get, "/api/pair/devices", "",
                             {{"Authorization", "Bearer " + guestToken}});
  ASSERT_EQ(r.status, 200);
  const auto j = json::parse(r.body);
  EXPECT_FALSE(j.at("you_are_owner").as_bool());
  for (const auto& d : j.at("devices").as_array()) {
    const bool isOwner = d.at("id").as_string() == ownerId;
    EXPECT_EQ(d.at("owner").as_bool(), isOwner);
    EXPECT_EQ(d.at("this_device").as_bool(), d.at("id").as_string() == guestId);
  }
}

}  // namespace
}  // namespace xr::web::test

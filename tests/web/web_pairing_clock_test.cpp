// The wall clock jumps (docs/security.md "The clock"): a Pi without a
// battery-backed clock starts on a stale time and is set by NTP or GPS later,
// by hours. A pairing code lives its 10 minutes and a lock-out its 5 minutes
// of elapsed time whatever the wall clock does, and the first device paired
// stays the owner.
#include <gtest/gtest.h>

#include "web/server/pairing.h"

namespace xr::web::test {
namespace {

constexpr std::int64_t kHourMs = 3'600'000;

struct ClockJump : ::testing::TestWithParam<std::int64_t> {
  std::int64_t wallMs = 1'700'000'000'000;
  std::int64_t elapsedMs = 5'000;
  std::shared_ptr<MemoryAuthStore> store = std::make_shared<MemoryAuthStore>();
  Pairing pairing{store, [this] { return wallMs; }, [this] { return elapsedMs; }};
  void pass(std::int64_t ms) {
    wallMs += ms;
    elapsedMs += ms;
  }
  void lockOut() {
    const auto right = pairing.newCode().code;
    const std::string wrong = right == "000000" ? "000001" : "000000";
    for (int i = 0; i < kMaxWrongTries; ++i) pairing.pair(wrong, "guesser");
  }
};

TEST_P(ClockJump, ACodeLivesItsLifetimeOfElapsedTime) {
  const auto code = pairing.newCode().code;
  pass(kCodeLifetimeMs - 1);
  wallMs += GetParam();  // the jump, just before the end
  EXPECT_EQ(pairing.pair(code, "phone").kind, Pairing::Outcome::Paired);
}

TEST_P(ClockJump, ACodeExpiresAtItsLifetimeOfElapsedTime) {
  const auto code = pairing.newCode().code;
  wallMs += GetParam();
  pass(kCodeLifetimeMs);
  EXPECT_EQ(pairing.pair(code, "phone").kind, Pairing::Outcome::WrongCode);
}

TEST_P(ClockJump, ALockOutLastsItsTimeOfElapsedTime) {
  lockOut();
  wallMs += GetParam();
  pass(kLockoutMs - 1);
  const auto during = pairing.pair("123456", "guesser");
  EXPECT_EQ(during.kind, Pairing::Outcome::LockedOut);
  EXPECT_EQ(during.retryAfterMs, 1);
  pass(1);
  EXPECT_EQ(pairing.pair("123456", "guesser").kind, Pairing::Outcome::WrongCode);
}

TEST_P(ClockJump, TheFirstDevicePairedStaysTheOwner) {
  const auto first = pairing.pair(pairing.newCode().code, "first");
  wallMs += GetParam();
  const auto second = pairing.pair(pairing.newCode().code, "second");
  ASSERT_EQ(second.kind, Pairing::Outcome::Paired);
  EXPECT_EQ(pairing.ownerId(), first.device.id);
  Pairing restarted{store, [this] { return wallMs; }, [this] { return elapsedMs; }};
  EXPECT_EQ(restarted.ownerId(), first.device.id);
}

INSTANTIATE_TEST_SUITE_P(ForwardAndBack, ClockJump,
                         ::testing::Values(+3 * kHourMs, -3 * kHourMs, +30 * 24 * kHourMs,
                                           -30 * 24 * kHourMs),
                         [](const auto& info) {
                           const auto h = info.param / kHourMs;
                           return (h > 0 ? "Forward" : "Back") + std::to_string(h > 0 ? h : -h) + "h";
                         });

}  // namespace
}  // namespace xr::web::test

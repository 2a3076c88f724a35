// The journal's rate limit for settings changes (2,000
// PATCHes wrote 2,000 lines; app/patch_log_limiter.h): a burst gives one
// line at once and one "suppressed N" summary once the minute has passed.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <spdlog/sinks/ringbuffer_sink.h>
#include <spdlog/spdlog.h>

#include "app/patch_log_limiter.h"
#include "store_test_util.h"
#include "web_api_rig.h"

namespace xr::app {
namespace {

using ::testing::HasSubstr;
using namespace std::chrono_literals;
using Clock = PatchLogLimiter::Clock;

TEST(PatchLogLimiter, ABurstGivesOneLineThenOneSummary) {
  PatchLogLimiter lim;
  const Clock::time_point t0{100s};
  std::vector<std::string> lines;
  for (int i = 0; i < 2000; ++i)
    if (auto l = lim.onPatch(t0 + i * 10ms, 2); !l.empty()) lines.push_back(l);  // 20 s of PATCHes
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_THAT(lines[0], HasSubstr("2 values"));
  EXPECT_EQ(lim.flush(t0 + 59s), "");  // still inside the minute
  const auto summary = lim.flush(t0 + 60s);
  EXPECT_THAT(summary, HasSubstr("suppressed 1999 more changes (3998 values)"));
  EXPECT_EQ(lim.flush(t0 + 200s), "");  // said once
}

TEST(PatchLogLimiter, AtTheIntervalAChangeIsLoggedJustBeforeItIsHeld) {
  PatchLogLimiter lim;
  const Clock::time_point t0{100s};
  EXPECT_NE(lim.onPatch(t0, 1), "");
  EXPECT_EQ(lim.onPatch(t0 + 60s - 1ns, 1), "");
  const auto l = lim.onPatch(t0 + 60s, 1);  // carries the one held back
  EXPECT_THAT(l, HasSubstr("suppressed 1"));
  EXPECT_EQ(lim.flush(t0 + 300s), "");  // nothing left to report
}

TEST(PatchLogLimiter, QuietChangesAreEachLogged) {
  PatchLogLimiter lim;
  const Clock::time_point t0{100s};
  for (int i = 0; i < 5; ++i) {
    const auto l = lim.onPatch(t0 + i * 61s, 1);
    EXPECT_THAT(l, HasSubstr("1 value;"));
    EXPECT_THAT(l, ::testing::Not(HasSubstr("suppressed")));
  }
}

// Through WebApi::patchParams, as the web server calls it: the journal gets
// the limiter's lines and nothing else about the burst.
TEST(WebApiPatchLog, ABurstOfPatchesWritesOneLineAndOneSummary) {
  auto sink = std::make_shared<spdlog::sinks::ringbuffer_sink_mt>(5000);
  auto previous = spdlog::default_logger();
  spdlog::set_default_logger(std::make_shared<spdlog::logger>("patch-log-test", sink));
  {
    xr::test::TempDir d;
    test::WebApiRig r(d.file("x.db"));
    const auto start = Clock::now();
    constexpr int kBurst = 200;
    for (int i = 0; i < kBurst; ++i) {
      const auto res = r.api->patchParams({{findParam("MaxDuty"), -1, i % 2 ? 95.0 : 96.0}}, "test");
      ASSERT_TRUE(res.errors.empty()) << res.errors[0].message;
    }
    r.api->flushPatchLog(start + 61s);
    std::vector<std::string> lines;
    for (auto& l : sink->last_formatted())
      if (l.find("parameters changed through the API") != std::string::npos) lines.push_back(l);
    ASSERT_EQ(lines.size(), 2u);  // before the limit: 200
    EXPECT_THAT(lines[0], HasSubstr("1 value;"));
    EXPECT_THAT(lines[1], HasSubstr("suppressed 199 more changes (199 values)"));
  }
  spdlog::set_default_logger(previous);
}

}  // namespace
}  // namespace xr::app

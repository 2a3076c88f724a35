// a command the regulator refuses is answered as refused,
// with the reason, not 200 "queued". A thread stands in for the control
// thread and applies the queued commands to a real Regulator, posting its
// answers the way ControlCycle does.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "app/web_api.h"
#include "control/regulator.h"

namespace xr::app {
namespace {

using ::testing::HasSubstr;

struct Rig {
  Params params;
  rt::Handoffs handoffs{params};
  Regulator regulator{params};
  std::atomic<bool> run{true};
  std::thread control;
  std::unique_ptr<WebApi> api;

  explicit Rig(bool ticking = true) {
    WebApiContext ctx;
    ctx.handoffs = &handoffs;
    ctx.commandAckTimeout = std::chrono::milliseconds(ticking ? 5000 : 50);
    api = std::make_unique<WebApi>(ctx);
    if (!ticking) return;
    control = std::thread([this] {
      while (run) {
        Command c;
        while (handoffs.commands.pop(c)) {
          const bool applied = regulator.command(c);
          if (c.ackId != 0) handoffs.acks.post(c.ackId, applied);
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
    });
  }
  ~Rig() {
    run = false;
    if (control.joinable()) control.join();
  }
};

TEST(CommandAck, ARefusedCommandIsNotAcceptedAndSaysWhy) {
  Rig r;
  Command c;
  c.type = CommandType::TuningCommit;  // TuningMode is off by default: the regulator refuses
  const web::CommandResult res = r.api->command(c);
  EXPECT_FALSE(res.accepted);  // before: true, "queued: tuning_commit"
  EXPECT_THAT(res.message, HasSubstr("refused by the regulator"));
  EXPECT_THAT(res.message, HasSubstr("TuningMode is off"));
}

TEST(CommandAck, AnAppliedCommandSaysApplied) {
  Rig r;
  Command c;
  c.type = CommandType::Manual;
  c.value = 20.0;
  const web::CommandResult res = r.api->command(c);
  EXPECT_TRUE(res.accepted);
  EXPECT_EQ(res.message, "applied: manual");
}

TEST(CommandAck, ManualDutyAtTheLimitIsAppliedJustOverItIsRefused) {
  Rig r;
  Command c;
  c.type = CommandType::Manual;
  c.value = 100.0;
  EXPECT_TRUE(r.api->command(c).accepted);
  c.value = 100.001;
  const web::CommandResult res = r.api->command(c);
  EXPECT_FALSE(res.accepted);
  EXPECT_THAT(res.message, HasSubstr("from 0 to 100 %"));
}

TEST(CommandAck, WithoutATickingLoopTheCommandStaysQueuedAndSaysSo) {
  Rig r(false);
  Command c;
  c.type = CommandType::Off;
  const web::CommandResult res = r.api->command(c);
  EXPECT_TRUE(res.accepted);
  EXPECT_THAT(res.message, HasSubstr("has not answered yet"));
  Command queued;
  ASSERT_TRUE(r.handoffs.commands.pop(queued));
  EXPECT_EQ(queued.type, CommandType::Off);
}

}  // namespace
}  // namespace xr::app

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <sys/stat.h>

#include <spdlog/spdlog.h>

#include "logging/journal.h"
#include "logging/logging.h"

namespace xr {
namespace {

using ::testing::HasSubstr;

Event lockoutStarted() {
  Event e;
  e.t = 12'500'000'000;
  e.level = EventLevel::Warning;
  e.code = EventCode::LockoutStarted;
  e.reason = Reason::REASON_INA_OVERVOLTAGE;
  e.mode = FieldControlMode::MODE_LOCKOUT_RAMP;
  e.a = 30;
  return e;
}

class CapturedJournal : public ::testing::Test {
 protected:
  void SetUp() override {
    logging::setJournalSender([this](const logging::JournalRecord& r) {
      records.push_back(r);
      return 0;
    });
  }
  void TearDown() override {
    logging::setJournalSender({});
    initLogging(LogSettings{}, std::nullopt, LogTarget::Console);
  }
  std::vector<logging::JournalRecord> records;
};

TEST(LogLevel, ParsesKnownNamesOnly) {
  EXPECT_EQ(parseLogLevel("debug"), spdlog::level::debug);
  EXPECT_EQ(parseLogLevel("warning"), spdlog::level::warn);
  EXPECT_EQ(parseLogLevel("off"), spdlog::level::off);
  EXPECT_FALSE(parseLogLevel("loud").has_value());
  EXPECT_FALSE(parseLogLevel("").has_value());
}

TEST(LogLevel, CommandLineWinsOverConfig) {
  LogSettings s;
  s.level = "error";
  EXPECT_EQ(initLogging(s, std::nullopt, LogTarget::Console), "");
  EXPECT_EQ(spdlog::default_logger()->level(), spdlog::level::err);
  EXPECT_EQ(initLogging(s, "debug", LogTarget::Console), "");
  EXPECT_EQ(spdlog::default_logger()->level(), spdlog::level::debug);
}

TEST(LogLevel, BadLevelIsReportedAndFallsBackToInfo) {
  LogSettings s;
  s.level = "loud";
  EXPECT_THAT(initLogging(s, std::nullopt, LogTarget::Console), HasSubstr("unknown log level \"loud\""));
  EXPECT_EQ(spdlog::default_logger()->level(), spdlog::level::info);
}

TEST(JournalPriority, MatchesSyslogLevels) {
  EXPECT_EQ(logging::journalPriority(EventLevel::Critical), 2);
  EXPECT_EQ(logging::journalPriority(EventLevel::Error), 3);
  EXPECT_EQ(logging::journalPriority(EventLevel::Warning), 4);
  EXPECT_EQ(logging::journalPriority(EventLevel::Info), 6);
  EXPECT_EQ(logging::journalPriority(EventLevel::Debug), 7);
  EXPECT_EQ(logging::journalPriorityForSpdlog(spdlog::level::warn), 4);
  EXPECT_EQ(logging::journalPriorityForSpdlog(spdlog::level::critical), 2);
}

TEST(EventRecord, CarriesSeedWordingAndStructuredFields) {
  const auto r = logging::eventRecord(lockoutStarted());
  EXPECT_EQ(r.field("MESSAGE"), "Field lockout started: 30s cooldown before restart allowed");
  EXPECT_EQ(r.field("PRIORITY"), "4");
  EXPECT_EQ(r.field("SYSLOG_IDENTIFIER"), "xregulatord");
  EXPECT_EQ(r.field("XREG_EVENT"), "LockoutStarted");
  EXPECT_EQ(r.field("XREG_REASON"), "REASON_INA_OVERVOLTAGE");
  EXPECT_EQ(r.field("XREG_MODE"), "MODE_LOCKOUT_RAMP");
  EXPECT_EQ(r.field("XREG_T_S"), "12.500");
}

TEST(EventRecord, NoReasonFieldWhenNothingIsActing) {
  Event e;
  e.code = EventCode::LockoutExpired;
  const auto r = logging::eventRecord(e);
  EXPECT_EQ(r.field("MESSAGE"), "Field lockout expired - normal operation resumed");
  EXPECT_EQ(r.field("XREG_REASON"), "");
}

TEST_F(CapturedJournal, EventsGoToTheJournalAsOneStructuredEntry) {
  initLogging(LogSettings{}, std::nullopt, LogTarget::Journal);
  EXPECT_TRUE(loggingToJournal());
  logEvent(lockoutStarted());
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(records[0].field("XREG_REASON"), "REASON_INA_OVERVOLTAGE");
  EXPECT_EQ(records[0].field("PRIORITY"), "4");
}

TEST_F(CapturedJournal, PlainLogLinesKeepTheirPriority) {
  initLogging(LogSettings{}, std::nullopt, LogTarget::Journal);
  spdlog::error("INA228 not answering");
  spdlog::debug("hidden at info level");
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(records[0].field("MESSAGE"), "INA228 not answering");
  EXPECT_EQ(records[0].field("PRIORITY"), "3");
}

TEST_F(CapturedJournal, EventsBelowTheLevelAreDropped) {
  LogSettings s;
  s.level = "error";
  initLogging(s, std::nullopt, LogTarget::Journal);
  logEvent(lockoutStarted());  // warning < error
  EXPECT_TRUE(records.empty());
}

TEST(ConsoleLog, ReadableLineWithSeedWordingFirst) {
  ::testing::internal::CaptureStderr();
  initLogging(LogSettings{}, std::nullopt, LogTarget::Console);
  EXPECT_FALSE(loggingToJournal());
  logEvent(lockoutStarted());
  spdlog::default_logger()->flush();
  const std::string out = ::testing::internal::GetCapturedStderr();
  EXPECT_THAT(out, HasSubstr("Field lockout started: 30s cooldown before restart allowed [event=LockoutStarted "
                             "reason=REASON_INA_OVERVOLTAGE mode=MODE_LOCKOUT_RAMP]"));
  EXPECT_THAT(out, HasSubstr("warn"));
}

TEST(JournalStream, MatchesOnlyTheDescriptorItNames) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  struct stat st {};
  ASSERT_EQ(fstat(fileno(f), &st), 0);
  const std::string env = std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino);
  EXPECT_TRUE(logging::journalStreamMatches(env.c_str(), fileno(f)));
  const std::string other = std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino + 1);
  EXPECT_FALSE(logging::journalStreamMatches(other.c_str(), fileno(f)));
  EXPECT_FALSE(logging::journalStreamMatches(nullptr, fileno(f)));
  EXPECT_FALSE(logging::journalStreamMatches("garbage", fileno(f)));
  std::fclose(f);
}

}  // namespace
}  // namespace xr

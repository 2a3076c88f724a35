// The daemon's side of updates (app/update_watch.h): the release record it
// shows, the quiet state the update gate reads, and the stop that starts an
// installed update only after the boat has been quiet long enough.
#include "app/update_watch.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace xr::app {
namespace {

namespace fs = std::filesystem;

class UpdateWatchTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("xr_update_watch_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "run");
    release_ = (dir_ / "release").string();
  }
  void TearDown() override { fs::remove_all(dir_); }
  void writeRelease(const std::string& version) {
    std::ofstream(release_) << "version=" << version
                            << "\nchannel=stable\ninstalled_at=2026-12-06T07:00:00Z\nprevious=0.9\n";
  }
  std::string stateText() const {
    std::ifstream in(dir_ / "run" / "state");
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }
  static Telemetry quiet() { return Telemetry{}; }
  static Telemetry running() {
    Telemetry t;
    t.rpm = 1800;
    t.field_enable = true;
    t.duty_pct = 40;
    return t;
  }
  fs::path dir_;
  std::string release_;
};

TEST_F(UpdateWatchTest, ReleaseRecordIsReadAndShownByVersion) {
  writeRelease("1.2-1");
  const ReleaseInfo r = readReleaseFile(release_);
  ASSERT_TRUE(r.known);
  EXPECT_EQ(r.channel, "stable");
  EXPECT_EQ(r.previous, "0.9");
  EXPECT_EQ(versionText("1.2", r),
            "xregulatord 1.2 (package 1.2-1, channel stable, installed 2026-12-06T07:00:00Z)");
  EXPECT_FALSE(readReleaseFile((dir_ / "missing").string()).known);
  EXPECT_EQ(versionText("1.2", ReleaseInfo{}), "xregulatord 1.2 (not installed from a package)");
}

TEST_F(UpdateWatchTest, BusyFromTheEngineSpeedThresholdTheFieldOrAnyDuty) {
  Telemetry t;
  t.rpm = kEngineTurningRpm - 0.1;
  EXPECT_FALSE(boatBusy(t));
  t.rpm = kEngineTurningRpm;
  EXPECT_TRUE(boatBusy(t));
  t.rpm = 0;
  t.field_enable = true;
  EXPECT_TRUE(boatBusy(t));
  t.field_enable = false;
  t.duty_pct = 0.5;
  EXPECT_TRUE(boatBusy(t));
}

TEST_F(UpdateWatchTest, WritesTheQuietStateForTheGateOnlyWhereTheRunDirectoryExists) {
  writeRelease("1");
  UpdateWatch w(release_, (dir_ / "run").string(), true);
  w.poll(running(), 42, 1000);
  EXPECT_NE(stateText().find("engine_running=1\nfield_on=1\nrpm=1800\nversion=1\n"), std::string::npos)
      << stateText();
  EXPECT_NE(stateText().find("updated_ms=1000\ntick=42\n"), std::string::npos) << stateText();
  w.poll(quiet(), 43, 2000);
  EXPECT_NE(stateText().find("engine_running=0\nfield_on=0\n"), std::string::npos) << stateText();

  UpdateWatch nowhere(release_, (dir_ / "absent").string(), true);
  nowhere.poll(quiet(), 1, 1000);
  EXPECT_FALSE(fs::exists(dir_ / "absent"));
}

TEST_F(UpdateWatchTest, InstalledUpdateWaitsWhileTheEngineRunsThenStopsAfterTenQuietSeconds) {
  writeRelease("1");
  UpdateWatch w(release_, (dir_ / "run").string(), true);
  for (int i = 0; i < 30; ++i) EXPECT_FALSE(w.poll(quiet(), 1, 0)) << "no update: never stops";
  writeRelease("2");
  for (int i = 0; i < 60; ++i) EXPECT_FALSE(w.poll(running(), 1, 0)) << "engine running: keeps regulating";
  web::VersionMap v;
  w.addTo(v);
  EXPECT_EQ(v["package"], "1");
  EXPECT_EQ(v["update"], "Update installed; starts when the engine stops (2)");
  for (int i = 1; i < kQuietSecondsBeforeRestart; ++i) EXPECT_FALSE(w.poll(quiet(), 1, 0)) << i << " s quiet";
  EXPECT_FALSE(w.poll(running(), 1, 0)) << "the engine restarted: the quiet count starts again";
  for (int i = 1; i < kQuietSecondsBeforeRestart; ++i) EXPECT_FALSE(w.poll(quiet(), 1, 0)) << i << " s quiet";
  EXPECT_TRUE(w.poll(quiet(), 1, 0)) << kQuietSecondsBeforeRestart
                                     << " s quiet: stop so the new version starts";
}

TEST_F(UpdateWatchTest, WithoutUpdateWatchItOnlySaysSo) {
  writeRelease("1");
  UpdateWatch w(release_, (dir_ / "run").string(), false);
  writeRelease("2");
  for (int i = 0; i < 3 * kQuietSecondsBeforeRestart; ++i) EXPECT_FALSE(w.poll(quiet(), 1, 0));
  web::VersionMap v;
  w.addTo(v);
  EXPECT_EQ(v["update"], "Update installed; starts when the engine stops (2)");
  EXPECT_EQ(v["channel"], "stable");
  EXPECT_EQ(v["installed"], "2026-12-06T07:00:00Z");
}

TEST_F(UpdateWatchTest, UnpackagedBuildSaysSoAndNeverStops) {
  UpdateWatch w(release_, (dir_ / "run").string(), true);
  for (int i = 0; i < 3 * kQuietSecondsBeforeRestart; ++i) EXPECT_FALSE(w.poll(quiet(), 1, 0));
  web::VersionMap v;
  w.addTo(v);
  EXPECT_EQ(v["package"], "not installed from a package");
}

}  // namespace
}  // namespace xr::app

#include "app/cli.h"

#include <gtest/gtest.h>

namespace xr::app {
namespace {

CliResult parse(std::vector<std::string> a) { return parseCommandLine(a); }

TEST(Cli, EmptyCommandLineRunsTheBoardWithDefaults) {
  const auto r = parse({});
  ASSERT_TRUE(r.ok());
  EXPECT_FALSE(r.options.sim);
  EXPECT_DOUBLE_EQ(r.options.speed, 1.0);
  EXPECT_DOUBLE_EQ(r.options.telemetryRateHz, 10.0);
}

TEST(Cli, ParsesEveryDesignOption) {
  const auto r = parse({"--config",
                        "a.toml",
                        "--sim",
                        "--scenario",
                        "s.toml",
                        "--speed",
                        "max",
                        "--duration",
                        "90",
                        "--telemetry-csv",
                        "t.csv",
                        "--telemetry-rate",
                        "20",
                        "--http",
                        "127.0.0.1:9000",
                        "--state-db",
                        "x.db",
                        "--seed",
                        "7",
                        "--log-level",
                        "debug",
                        "--sim-outputs",
                        "o.txt"});
  ASSERT_TRUE(r.ok()) << r.error;
  const auto& o = r.options;
  EXPECT_EQ(*o.config, "a.toml");
  EXPECT_TRUE(o.sim);
  EXPECT_EQ(*o.scenario, "s.toml");
  EXPECT_DOUBLE_EQ(o.speed, 0.0);  // max
  EXPECT_DOUBLE_EQ(*o.durationS, 90.0);
  EXPECT_EQ(*o.telemetryCsv, "t.csv");
  EXPECT_DOUBLE_EQ(o.telemetryRateHz, 20.0);
  EXPECT_EQ(*o.http, "127.0.0.1:9000");
  EXPECT_EQ(*o.stateDb, "x.db");
  EXPECT_EQ(*o.seed, 7u);
  EXPECT_EQ(*o.logLevel, "debug");
  EXPECT_EQ(*o.simOutputs, "o.txt");
}

TEST(Cli, AcceptsEqualsForm) {
  const auto r = parse({"--sim", "--speed=10", "--duration=5"});
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_DOUBLE_EQ(r.options.speed, 10.0);
  EXPECT_DOUBLE_EQ(*r.options.durationS, 5.0);
}

TEST(Cli, FlagsWithoutValues) {
  for (const char* f : {"--check-config", "--print-default-config", "--probe", "--version"}) {
    auto r = parse({f, "--config", "x"});
    EXPECT_TRUE(r.ok()) << f << ": " << r.error;
  }
  EXPECT_FALSE(parse({"--version=1"}).ok());
}

TEST(Cli, RejectsBadValuesNamingTheOption) {
  struct Case {
    std::vector<std::string> args;
    const char* mentions;
  } cases[] = {
      {{"--sim", "--speed", "fast"}, "--speed"},
      {{"--sim", "--speed", "0"}, "--speed"},
      {{"--sim", "--speed", "-2"}, "--speed"},
      {{"--duration", "abc"}, "--duration"},
      {{"--duration", "0"}, "--duration"},
      {{"--telemetry-rate", "0"}, "--telemetry-rate"},
      {{"--telemetry-rate", "1e9"}, "--telemetry-rate"},
      {{"--sim", "--seed", "-1"}, "--seed"},
      {{"--sim", "--seed", "1.5"}, "--seed"},
      {{"--config"}, "--config"},
      {{"--frobnicate"}, "--frobnicate"},
      {{"stray"}, "stray"},
      {{"--sim", "--test-fault", "melt"}, "--test-fault"},
  };
  for (const auto& c : cases) {
    const auto r = parse(c.args);
    EXPECT_FALSE(r.ok()) << c.args[0];
    EXPECT_NE(r.error.find(c.mentions), std::string::npos) << r.error;
  }
}

// The address gets the check [web] listen gets, before any device opens:
// a value the config file refuses with 78 is refused here with 78 too,
// never "running without the dashboard".
TEST(Cli, HttpAddressThatIsNotAnIpAddressExitsAsABadConfigValue) {
  for (const char* bad : {"256.0.0.1:8104", "localhost:8104", "boat.local:80", "127.0.0.1", "127.0.0.1:65536",
                          "127.0.0.1:80x", "[::1:80", "127.0.0.1:"}) {
    const auto r = parse({"--sim", "--http", bad});
    EXPECT_FALSE(r.ok()) << bad;
    EXPECT_EQ(r.exitCode, 78) << bad;
    EXPECT_NE(r.error.find("--http"), std::string::npos) << r.error;
  }
  EXPECT_NE(parse({"--http", "localhost:8104"}).error.find("is not an IP address"), std::string::npos);
}

TEST(Cli, HttpAcceptsAddressLiteralsAndAnEmptyHostForEveryInterface) {
  for (const char* good :
       {"127.0.0.1:8104", "0.0.0.0:8104", "[::1]:8104", "[::]:0", ":8104", "127.0.0.1:65535"}) {
    const auto r = parse({"--sim", "--http", good});
    EXPECT_TRUE(r.ok()) << good << ": " << r.error;
  }
}

TEST(Cli, AUsageErrorStillExits64) { EXPECT_EQ(parse({"--bogus"}).exitCode, 64); }

TEST(Cli, SimulationOnlyOptionsNeedSim) {
  EXPECT_FALSE(parse({"--scenario", "s.toml"}).ok());
  EXPECT_FALSE(parse({"--speed", "2"}).ok());
  EXPECT_FALSE(parse({"--sim-outputs", "o"}).ok());
  EXPECT_FALSE(parse({"--seed", "3"}).ok());
  EXPECT_FALSE(parse({"--test-fault", "segv"}).ok());  // never on a real board
  EXPECT_TRUE(parse({"--sim", "--test-fault", "segv", "--test-fault-at", "2"}).ok());
  EXPECT_FALSE(parse({"--sim", "--test-fault-at", "2"}).ok());
}

TEST(Cli, CheckConfigNeedsAFile) {
  EXPECT_FALSE(parse({"--check-config"}).ok());
  EXPECT_TRUE(parse({"--check-config", "--config", "x.toml"}).ok());
}

TEST(Cli, UpdateOptionsDefaultToThePackagePathsAndAreOff) {
  const CliResult d = parse({});
  ASSERT_TRUE(d.ok());
  EXPECT_FALSE(d.options.updateWatch);
  EXPECT_EQ(d.options.releaseFile, "/var/lib/xregulator/release");
  EXPECT_EQ(d.options.runDir, "/run/xregulator");
  const CliResult r = parse({"--update-watch", "--release-file", "/tmp/r", "--run-dir=/tmp/run"});
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_TRUE(r.options.updateWatch);
  EXPECT_EQ(r.options.releaseFile, "/tmp/r");
  EXPECT_EQ(r.options.runDir, "/tmp/run");
  EXPECT_FALSE(parse({"--release-file"}).ok());
}

// The update gate takes /run/xregulator/state as the running regulator's
// word: a --sim daemon on the same board (an installer trying the dashboard)
// must not write it, or its stopped simulated engine would let an update
// through under a running one.
TEST(Cli, ASimulationWritesNoGateStateFileUnlessToldWhere) {
  const CliResult sim = parse({"--sim"});
  ASSERT_TRUE(sim.ok()) << sim.error;
  EXPECT_EQ(sim.options.runDir, "");
  const CliResult told = parse({"--sim", "--run-dir", "/run/xregulator"});
  ASSERT_TRUE(told.ok()) << told.error;
  EXPECT_EQ(told.options.runDir, "/run/xregulator");
  EXPECT_EQ(parse({"--run-dir", "/tmp/run", "--sim"}).options.runDir, "/tmp/run");
}

TEST(Cli, UsageListsTheDesignOptions) {
  const std::string u = usageText();
  for (const char* o :
       {"--config", "--sim", "--scenario", "--speed", "--duration", "--telemetry-csv", "--telemetry-rate",
        "--http", "--state-db", "--check-config", "--print-default-config", "--probe", "--version", "--seed",
        "--log-level", "--sim-outputs"})
    EXPECT_NE(u.find(o), std::string::npos) << o;
  EXPECT_EQ(u.find("--test-fault"), std::string::npos);  // hidden
}

}  // namespace
}  // namespace xr::app

// Config robustness (docs/security.md): a hostile or broken file, [web]
// listen checked by the loader, the token's rules.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "config/bounded_read.h"
#include "config/config.h"
#include "config/web_checks.h"
#include "test_files.h"

namespace xr {
namespace {

using ::testing::HasSubstr;
using xr::testing::TempFile;

std::vector<std::string> messages(std::string_view text) {
  std::vector<std::string> m;
  for (const auto& e : loadConfigString(text, "test.toml").errors) m.push_back(e.toString());
  return m;
}

struct TempDirectory {
  std::string path;
  TempDirectory() {
    char tmpl[] = "/tmp/xr-config-dir-XXXXXX";
    path = mkdtemp(tmpl);
  }
  ~TempDirectory() { std::filesystem::remove_all(path); }
};

int checkExit(const std::string& path, std::string& err) {
  std::ostringstream o, e;
  const int rc = checkConfigMain(path, o, e);
  err = e.str();
  return rc;
}

TEST(ConfigFile, ADirectoryIsRefusedNotReadAsEmptyDefaults) {
  TempDirectory d;
  std::string err;
  EXPECT_EQ(checkExit(d.path, err), 78);
  EXPECT_THAT(err, HasSubstr("is a directory, not a configuration file"));
}

TEST(ConfigFile, AFifoWithoutWriterIsRefusedWithoutBlocking) {
  TempDirectory d;
  const std::string fifo = d.path + "/fifo.toml";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  std::string err;
  EXPECT_EQ(checkExit(fifo, err), 78);  // before the fix: blocks in open() forever
  EXPECT_THAT(err, HasSubstr("is a FIFO (named pipe), not a configuration file"));
}

TEST(ConfigFile, AnEndlessDeviceIsRefusedBeforeReading) {
  std::string err;
  EXPECT_EQ(checkExit("/dev/zero", err), 78);
  EXPECT_THAT(err, HasSubstr("/dev/zero: is a character device, not a configuration file"));
}

TEST(ConfigFile, AFileOverTheSizeBoundIsRefusedAndOneJustUnderIsRead) {
  TempDirectory d;
  const std::string big = d.path + "/big.toml";
  {
    std::ofstream f(big);
    f << "# " << std::string(kMaxConfigBytes - 3, 'x') << "\n";  // exactly kMaxConfigBytes
  }
  std::string text;
  EXPECT_EQ(readConfigText(big, text), "");
  EXPECT_EQ(text.size(), kMaxConfigBytes);
  {
    std::ofstream f(big, std::ios::app);
    f << "\n";
  }
  EXPECT_THAT(readConfigText(big, text), HasSubstr("a configuration file is at most 1048576 bytes"));
}

TEST(ConfigFile, ASymlinkToARegularFileIsFine) {
  TempFile f("[web]\nport = 8081\n");
  TempDirectory d;
  const std::string link = d.path + "/link.toml";
  ASSERT_EQ(symlink(f.path().c_str(), link.c_str()), 0);
  const LoadResult r = loadConfigFile(link);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.config->settings.web.port, 8081);
}

TEST(WebListen, AHostNameIsAConfigErrorAtItsLine) {
  const auto m = messages("[web]\nport = 8080\nlisten = \"localhost\"\n");
  ASSERT_EQ(m.size(), 1u);
  EXPECT_THAT(m[0], HasSubstr("test.toml:3:1: web.listen: 'localhost' is not an IP address"));
  TempFile f("[web]\nlisten = \"localhost\"\n");
  std::string err;
  EXPECT_EQ(checkExit(f.path(), err), 78);
}

TEST(WebListen, AddressLiteralsAreAccepted) {
  for (const char* a : {"127.0.0.1", "0.0.0.0", "::", "::1", "fe80::1", "192.168.4.1"}) {
    EXPECT_TRUE(messages(std::string("[web]\nlisten = \"") + a + "\"\n").empty()) << a;
    EXPECT_TRUE(isNumericListenAddress(a)) << a;
  }
  for (const char* a : {"", "localhost", "127.0.0.1:8080", "256.1.1.1", "[::1]", " 127.0.0.1"})
    EXPECT_FALSE(isNumericListenAddress(a)) << a;
}

TEST(WebToken, ShortOrSpacedTokensAreRefusedAtTheLimit) {
  EXPECT_TRUE(messages("[web]\ntoken = \"\"\n").empty());  // generated
  const std::string atLimit(kMinTokenLength, 'a');
  const std::string belowLimit(kMinTokenLength - 1, 'a');
  EXPECT_TRUE(messages("[web]\ntoken = \"" + atLimit + "\"\n").empty());
  const auto m = messages("[web]\ntoken = \"" + belowLimit + "\"\n");
  ASSERT_EQ(m.size(), 1u);
  EXPECT_THAT(m[0], HasSubstr("web.token: is 15 characters; a token needs at least 16"));
  EXPECT_EQ(messages("[web]\ntoken = \"x\"\n").size(), 1u);
  EXPECT_THAT(messages("[web]\ntoken = \"a token with spaces in it\"\n").at(0),
              HasSubstr("printable ASCII characters without spaces"));
}

TEST(WebToken, FingerprintIsShortStableAndDiffers) {
  const std::string t(64, 'f');
  EXPECT_EQ(tokenFingerprint(t).size(), 8u);
  EXPECT_EQ(tokenFingerprint(t), tokenFingerprint(t));
  EXPECT_NE(tokenFingerprint(t), tokenFingerprint(std::string(63, 'f') + "e"));
  EXPECT_EQ(tokenFingerprint(t).find("ffff"), std::string::npos);  // not a piece of the token
}

TEST(WebToken, ATokenInAWorldReadableFileIsWarnedAbout) {
  TempFile f("[web]\ntoken = \"0123456789abcdef0123\"\n");
  ASSERT_EQ(chmod(f.path().c_str(), 0644), 0);
  EXPECT_THAT(tokenFileWarning(f.path(), "0123456789abcdef0123"),
              HasSubstr("every user of this machine can read"));
  ASSERT_EQ(chmod(f.path().c_str(), 0640), 0);
  EXPECT_EQ(tokenFileWarning(f.path(), "0123456789abcdef0123"), "");
  ASSERT_EQ(chmod(f.path().c_str(), 0644), 0);
  EXPECT_EQ(tokenFileWarning(f.path(), ""), "");  // no token in the file: nothing to protect
}

}  // namespace
}  // namespace xr

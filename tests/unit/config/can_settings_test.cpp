// [can] (docs/integrations.md): values the CAN service could never use are configuration
// errors at their line (--check-config exits 78 on them).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>

#include "config/config.h"
#include "test_files.h"

namespace xr {
namespace {

using ::testing::HasSubstr;

std::vector<std::string> messages(std::string_view text) {
  std::vector<std::string> m;
  for (const auto& e : loadConfigString(text, "test.toml").errors) m.push_back(e.toString());
  return m;
}

TEST(CanSettings, TheDefaultsAndAUsualBoardAreAccepted) {
  EXPECT_TRUE(messages("").empty());
  EXPECT_TRUE(messages("[can]\nbms_interface = \"can0\"\nbms_protocol = \"pylontech\"\n"
                       "n2k_interface = \"can1\"\nRpmSource = \"n2k\"\n")
                  .empty());
}

TEST(CanSettings, RpmFromN2kNeedsTheN2kBus) {
  const auto m = messages("[can]\nbms_interface = \"can0\"\nRpmSource = \"n2k\"\n");
  ASSERT_EQ(m.size(), 1u);
  EXPECT_THAT(m[0], HasSubstr("test.toml:3"));
  EXPECT_THAT(m[0], HasSubstr("n2k_interface"));
  xr::testing::TempFile f("[can]\nRpmSource = \"n2k\"\n");
  std::ostringstream out, err;
  EXPECT_EQ(checkConfigMain(f.path(), out, err), 78);  // what --check-config returns
  EXPECT_THAT(err.str(), HasSubstr("can.RpmSource"));
}

TEST(CanSettings, InterfaceNamesTheKernelCouldNeverHaveAreRefused) {
  auto m = messages("[can]\nbms_interface = \"can0 \"\n");
  ASSERT_EQ(m.size(), 1u);
  EXPECT_THAT(m[0], HasSubstr("test.toml:2"));
  m = messages("[can]\nn2k_interface = \"/dev/can1\"\n");
  ASSERT_EQ(m.size(), 1u);
  m = messages("[can]\nn2k_interface = \"can0123456789abc\"\n");  // 16 bytes: one too many
  ASSERT_EQ(m.size(), 1u);
  EXPECT_TRUE(messages("[can]\nn2k_interface = \"can0123456789ab\"\n").empty());  // 15: the limit
}

TEST(CanSettings, DotNamesLoopbackAndMarkupAreNoCanInterface) {
  for (const char* name : {".", "..", "lo", "<b>x", "can0;reboot", "can\\u00e90"}) {
    const auto m = messages(std::string("[can]\nbms_interface = \"") + name + "\"\n");
    ASSERT_EQ(m.size(), 1u) << name;
    EXPECT_THAT(m[0], HasSubstr("not a CAN interface name")) << name;
  }
  for (const char* name : {"can0", "vcan0", "slcan0", "can-house", "can_1", "can0.1", "lo0"})
    EXPECT_TRUE(messages(std::string("[can]\nn2k_interface = \"") + name + "\"\n").empty()) << name;
}

TEST(CanSettings, TheTwoBusesAreNotOneInterface) {
  const auto m = messages("[can]\nbms_interface = \"can0\"\nn2k_interface = \"can0\"\n");
  ASSERT_EQ(m.size(), 1u);
  EXPECT_THAT(m[0], HasSubstr("bit rates"));
}

TEST(CanSettings, AnUnknownProtocolOrRpmSourceIsRefused) {
  EXPECT_TRUE(messages("[can]\nbms_protocol = \"rec\"\n").empty());
  const auto m = messages("[can]\nbms_protocol = \"jk\"\n");
  ASSERT_EQ(m.size(), 1u);
  EXPECT_THAT(m[0], HasSubstr("test.toml:2"));
  // The message lists what is valid.
  EXPECT_THAT(m[0], HasSubstr("victron"));
  EXPECT_THAT(m[0], HasSubstr("pylontech"));
  EXPECT_THAT(m[0], HasSubstr("rec"));
  xr::testing::TempFile f("[can]\nbms_protocol = \"jk\"\n");
  std::ostringstream out, err;
  EXPECT_EQ(checkConfigMain(f.path(), out, err), 78);
  EXPECT_THAT(err.str(), HasSubstr("bms_protocol"));
  EXPECT_EQ(messages("[can]\nRpmSource = \"w-terminal\"\n").size(), 1u);
}

}  // namespace
}  // namespace xr

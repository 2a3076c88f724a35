// The check in front of toml++ (config/toml_text_guard.h, docs/security.md):
// what would reach toml++ 3.3.0's TOML_UNREACHABLE is refused at its line
// and column; what TOML allows (non-ASCII in strings and comments) passes.
#include "config/toml_text_guard.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "config/config.h"

namespace xr {
namespace {

TEST(TomlTextGuard, NonAsciiAfterABareKeyIsRefusedAtItsColumn) {
  const auto p = tomlTextProblem("name = \"x\"\n[battery]\ncapacity_\xC6\x97 = 400\n");  // U+0197
  ASSERT_TRUE(p.has_value());
  EXPECT_EQ(p->line, 3);
  EXPECT_EQ(p->column, 10);
  EXPECT_NE(p->message.find("outside a string or comment"), std::string_view::npos);
}

TEST(TomlTextGuard, NonAsciiAnywhereOutsideStringsIsRefused) {
  for (const char* text : {"a = 1\xC2\xA1\n", "\xE2\xB3\xAE = 1\n", "[t\xEF\xAF\xB6]\n",
                           "a = [1, \xC3\xA9]\n", "a = \"x\" \xC3\xA9\n", "\xEF\xBB\xBF\xEF\xBB\xBF = 1\n"})
    EXPECT_TRUE(tomlTextProblem(text).has_value()) << text;
}

TEST(TomlTextGuard, NonAsciiInStringsAndCommentsPasses) {
  for (const char* text : {"# caf\xC3\xA9 \xC6\x97\nname = \"Ɨ caf\xC3\xA9\"\n", "name = 'caf\xC3\xA9'\n",
                           "\"caf\xC3\xA9\" = 1\n", "a = \"\"\"\nl\xC3\xA9 \"\" \"\"\"\"\nb = 1 # \xC3\xA9\n",
                           "a = '''\n\xC3\xA9 '' '''''\nb = 2\n", "a = \"esc \\\" \xC3\xA9\"\n",
                           "a = \"\"\"\\n\xC3\xA9\"\"\"\n", "\xEF\xBB\xBFname = \"x\"\n"})
    EXPECT_FALSE(tomlTextProblem(text).has_value()) << text;
}

TEST(TomlTextGuard, AStringEndsWhereTomlEndsIt) {
  // After a multi-line string closed by five quotes, and after a literal
  // string, the scan is outside again.
  EXPECT_TRUE(tomlTextProblem("a = \"\"\"x\"\"\"\"\"\n\xC3\xA9 = 1\n").has_value());
  EXPECT_TRUE(tomlTextProblem("a = 'x' \xC3\xA9\n").has_value());
  // A single-line string broken by a newline (toml++ refuses it) does not
  // hide the next line.
  const auto p = tomlTextProblem("a = \"x\n\xC3\xA9 = 1\n");
  ASSERT_TRUE(p.has_value());
  EXPECT_EQ(p->line, 2);
  EXPECT_EQ(p->column, 1);
}

TEST(TomlTextGuard, NonAsciiAfterABackslashInAMultiLineStringIsRefused) {
  // toml++ asks is_whitespace() of these too (parser.inl, line-ending
  // backslashes): right after the backslash, after its spaces, after the
  // line break it trims.
  for (const char* text : {"a = \"\"\"\\\xC6\x97\"\"\"\n", "a = \"\"\"\\  \xC6\x97\"\"\"\n",
                           "a = \"\"\"x\\\n   \xC6\x97\"\"\"\n"}) {
    const auto p = tomlTextProblem(text);
    ASSERT_TRUE(p.has_value()) << text;
    EXPECT_NE(p->message.find("backslash"), std::string_view::npos);
  }
  // A line-ending backslash followed by ASCII is fine.
  EXPECT_FALSE(tomlTextProblem("a = \"\"\"x\\\n   y \xC6\x97\"\"\"\n").has_value());
}

TEST(TomlTextGuard, ColumnsCountCharactersNotBytes) {
  const auto p = tomlTextProblem("a = \"\xC3\xA9\xC3\xA9\" \xC3\xA9\n");
  ASSERT_TRUE(p.has_value());
  EXPECT_EQ(p->column, 10);
}

TEST(TomlTextGuard, TheConfigLoaderRefusesTheFuzzFindingWithFileLineColumn) {
  std::ifstream f(
      std::filesystem::path(XR_SOURCE_DIR) / "tests/fuzz/regressions/non-ascii-after-bare-key.toml",
      std::ios::binary);
  ASSERT_TRUE(f) << "the kept regression input";
  std::stringstream ss;
  ss << f.rdbuf();
  const LoadResult r = loadConfigString(ss.str(), "finding.toml");
  ASSERT_FALSE(r.ok());
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_EQ(r.errors[0].toString().rfind("finding.toml:4:10: non-ASCII character outside a string", 0), 0u)
      << r.errors[0].toString();
}

}  // namespace
}  // namespace xr

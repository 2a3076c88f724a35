#include "config/toml_text_guard.h"

namespace xr {

namespace {
enum class State { Normal, Comment, Basic, Literal, MultiBasic, MultiLiteral };

constexpr std::string_view kOutside =
    "non-ASCII character outside a string or comment (TOML allows it only inside quotes or after #)";
constexpr std::string_view kAfterBackslash =
    "non-ASCII character right after a backslash (and its whitespace) in a multi-line string: not "
    "accepted (the TOML library mishandles it); write it on the line before or use a \\u escape";

bool startsWith(std::string_view text, std::size_t i, std::string_view s) {
  return text.substr(i, s.size()) == s;
}

// The closing delimiter of a multi-line string is the last three of a run
// of three to five quotes (TOML 1.0: one or two may end the content).
std::size_t closingRun(std::string_view text, std::size_t i, char q) {
  std::size_t n = 0;
  while (n < 5 && i + n < text.size() && text[i + n] == q) ++n;
  return n;
}

bool asciiSpace(unsigned char b) { return b == ' ' || b == '\t' || b == '\r' || b == '\n'; }
}  // namespace

std::optional<TomlTextProblem> tomlTextProblem(std::string_view text) {
  State st = State::Normal;
  TomlTextProblem pos{1, 1, {}};
  std::size_t i = startsWith(text, 0, "\xEF\xBB\xBF") ? 3 : 0;
  // Advances over n bytes of text, keeping the line and column.
  auto step = [&](std::size_t n) {
    for (std::size_t k = 0; k < n && i < text.size(); ++k, ++i) {
      const auto b = static_cast<unsigned char>(text[i]);
      if (b == '\n') {
        ++pos.line;
        pos.column = 1;
      } else if ((b & 0xC0) != 0x80) {  // not a UTF-8 continuation byte
        ++pos.column;
      }
    }
  };
  auto problem = [&](std::string_view message) {
    pos.message = message;
    return pos;
  };
  while (i < text.size()) {
    const auto b = static_cast<unsigned char>(text[i]);
    switch (st) {
      case State::Normal:
        if (b >= 0x80) return problem(kOutside);
        if (b == '#') {
          st = State::Comment;
        } else if (startsWith(text, i, "\"\"\"")) {
          st = State::MultiBasic;
          step(3);
          continue;
        } else if (startsWith(text, i, "'''")) {
          st = State::MultiLiteral;
          step(3);
          continue;
        } else if (b == '"') {
          st = State::Basic;
        } else if (b == '\'') {
          st = State::Literal;
        }
        break;
      case State::Comment:
        if (b == '\n') st = State::Normal;
        break;
      case State::Basic:
        if (b == '\\') {  // an escape: the next byte cannot end the string
          step(2);
          continue;
        }
        if (b == '"' || b == '\n') st = State::Normal;  // a newline: toml++ refuses it
        break;
      case State::MultiBasic:
        if (b == '\\') {
          step(1);
          while (i < text.size() && asciiSpace(static_cast<unsigned char>(text[i]))) step(1);
          if (i < text.size() && static_cast<unsigned char>(text[i]) >= 0x80) return problem(kAfterBackslash);
          step(1);  // the escaped character (or the first after the line-ending backslash)
          continue;
        }
        if (startsWith(text, i, "\"\"\"")) {
          st = State::Normal;
          step(closingRun(text, i, '"'));
          continue;
        }
        break;
      case State::Literal:
        if (b == '\'' || b == '\n') st = State::Normal;
        break;
      case State::MultiLiteral:
        if (startsWith(text, i, "'''")) {
          st = State::Normal;
          step(closingRun(text, i, '\''));
          continue;
        }
        break;
    }
    step(1);
  }
  return std::nullopt;
}

}  // namespace xr

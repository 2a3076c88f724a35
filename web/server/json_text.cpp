// The web API's JSON writer: Boost.JSON for structure and string escaping,
// plain decimals for doubles (json_text.h).
#include "web/server/json_text.h"

#include <array>
#include <charconv>
#include <cmath>

namespace xr::web {
namespace json = boost::json;

void appendJsonNumber(std::string& out, double v) {
  if (!std::isfinite(v)) {
    out += "null";
    return;
  }
  if (v == 0.0) v = 0.0;  // "-0" reads oddly on a dashboard; -0.0 == 0.0
  // Shortest round-trip in fixed notation: 13.01 -> "13.01", 1e-7 ->
  // "0.0000001". A double's fixed form is at most ~330 characters.
  std::array<char, 400> buf{};
  const auto r = std::to_chars(buf.data(), buf.data() + buf.size(), v, std::chars_format::fixed);
  out.append(buf.data(), r.ptr);
}

namespace {

void write(std::string& out, const json::value& v);

void writeObject(std::string& out, const json::object& o) {
  out += '{';
  bool first = true;
  for (const auto& kv : o) {
    if (!first) out += ',';
    first = false;
    out += json::serialize(json::string_view(kv.key()));
    out += ':';
    write(out, kv.value());
  }
  out += '}';
}

void writeArray(std::string& out, const json::array& a) {
  out += '[';
  bool first = true;
  for (const auto& e : a) {
    if (!first) out += ',';
    first = false;
    write(out, e);
  }
  out += ']';
}

void write(std::string& out, const json::value& v) {
  switch (v.kind()) {
    case json::kind::object:
      writeObject(out, v.get_object());
      return;
    case json::kind::array:
      writeArray(out, v.get_array());
      return;
    case json::kind::double_:
      appendJsonNumber(out, v.get_double());
      return;
    default:  // null, bool, integers and strings: Boost.JSON's text is right
      out += json::serialize(v);
      return;
  }
}

}  // namespace

std::string jsonText(const json::value& v) {
  std::string out;
  out.reserve(256);
  write(out, v);
  return out;
}

}  // namespace xr::web

// Replies and parsing shared by the API routes (api_reply.h).
#include "web/server/api_reply.h"

#include <charconv>
#include <cmath>

#include "web/server/json_text.h"

namespace xr::web::api {

Response reply(const Request& req, http::status status, std::string body, std::string_view contentType) {
  Response res{status, req.version()};
  res.set(http::field::server, "xregulatord");
  res.set(http::field::content_type, contentType);
  res.set(http::field::cache_control, "no-store");
  res.set("X-Content-Type-Options", "nosniff");
  res.keep_alive(req.keep_alive());
  res.body() = std::move(body);
  res.prepare_payload();
  return res;
}

Response jsonReply(const Request& req, http::status status, const json::value& v) {
  return reply(req, status, jsonText(v));
}

Response error(const Request& req, http::status status, std::string_view message) {
  json::object o;
  o["error"] = message;
  auto res = jsonReply(req, status, o);
  if (status == http::status::unauthorized)
    res.set(http::field::www_authenticate, "Bearer realm=\"xregulator\"");
  return res;
}

Response authError(const Request& req, unsigned code) {
  return code == 401
             ? error(req, http::status::unauthorized, "missing token: send Authorization: Bearer <token>")
             : error(req, http::status::forbidden, "invalid token");
}

std::optional<double> parseDouble(std::string_view s) {
  if (s.empty()) return std::nullopt;
  double v = 0;
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc{} || p != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

std::optional<std::int64_t> parseInt(std::string_view s) {
  if (s.empty()) return std::nullopt;
  std::int64_t v = 0;
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc{} || p != s.data() + s.size()) return std::nullopt;
  return v;
}

// A JSON number as double (int64, uint64 or double), nullopt otherwise.
std::optional<double> jsonNumber(const json::value& v) {
  if (v.is_double()) return v.get_double();
  if (v.is_int64()) return static_cast<double>(v.get_int64());
  if (v.is_uint64()) return static_cast<double>(v.get_uint64());
  return std::nullopt;
}

std::optional<json::value> parseBody(const Request& req, std::string& err) {
  boost::system::error_code ec;
  json::parse_options po;
  po.max_depth = 16;
  json::value v = json::parse(req.body(), ec, {}, po);
  if (ec) {
    err = "malformed JSON: " + ec.message();
    return std::nullopt;
  }
  return v;
}

}  // namespace xr::web::api

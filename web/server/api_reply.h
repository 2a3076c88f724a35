#pragma once
// The small pieces every API route uses to answer: JSON and error replies
// with the server's headers, and strict number parsing of query strings and
// JSON bodies. Internal to web/server (the routes live in api_*.cpp).
#include <boost/json.hpp>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "web/server/api_handler.h"

namespace xr::web::api {

namespace json = boost::json;

Response reply(const Request& req, http::status status, std::string body,
               std::string_view contentType = "application/json");
Response jsonReply(const Request& req, http::status status, const json::value& v);
// {"error": message}; a 401 also names the Bearer realm.
Response error(const Request& req, http::status status, std::string_view message);
// 401 (no token) or 403 (wrong token) from checkRead()'s code.
Response authError(const Request& req, unsigned code);

// Whole-string parses: trailing text, NaN or infinity give nullopt.
std::optional<double> parseDouble(std::string_view s);
std::optional<std::int64_t> parseInt(std::string_view s);
// A JSON number as double (int64, uint64 or double), nullopt otherwise.
std::optional<double> jsonNumber(const json::value& v);
// The request body as JSON (depth at most 16), or err set.
std::optional<json::value> parseBody(const Request& req, std::string& err);

}  // namespace xr::web::api

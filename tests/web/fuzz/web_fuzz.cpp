// libFuzzer target (docs/security.md): arbitrary bytes through the request/JSON
// handling. The first byte picks the entry point:
//   0: raw HTTP request bytes -> Beast parser (with the server's limits) -> ApiHandler
//   1: PATCH /api/params body   2: POST /api/commands body
//   3: GET target (query parsing of /api/events, /api/history, static paths)
// Any crash, sanitizer report or uncaught exception is a finding.
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <cstddef>
#include <cstdint>
#include <string>

#include "tests/web/fake_daemon_api.h"
#include "web/server/api_handler.h"

namespace {
using namespace xr::web;

struct World {
  test::FakeDaemonApi api;
  WebServerOptions opts;
  ApiHandler handler{api, opts};
  World() {
    opts.token = "fuzz-token";
    opts.www_root = "/nonexistent-xr-www";
    api.publish();
  }
};

World& world() {
  static World w;
  return w;
}

void check(const Response& res) {
  // Every answer is a well-formed status; errors are 4xx, never 5xx.
  const unsigned code = res.result_int();
  if (code < 200 || code >= 600 || code == 500) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  auto& w = world();
  const std::string rest(reinterpret_cast<const char*>(data + 1), size - 1);
  switch (data[0] % 4) {
    case 0: {
      http::request_parser<http::string_body> parser;
      parser.header_limit(8 * 1024);
      parser.body_limit(64 * 1024);
      parser.eager(true);
      boost::beast::error_code ec;
      parser.put(boost::asio::buffer(rest), ec);
      if (!ec && parser.is_done()) check(w.handler.handle(parser.release()));
      break;
    }
    case 1:
    case 2: {
      Request req{data[0] % 4 == 1 ? http::verb::patch : http::verb::post,
                  data[0] % 4 == 1 ? "/api/params" : "/api/commands", 11};
      req.set(http::field::authorization, "Bearer fuzz-token");
      req.body() = rest;
      req.prepare_payload();
      check(w.handler.handle(req));
      break;
    }
    default: {
      Request req{http::verb::get, rest, 11};
      check(w.handler.handle(req));
      break;
    }
  }
  return 0;
}

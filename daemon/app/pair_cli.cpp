// `xregulatord --pair` (pair_cli.h).
#include "app/pair_cli.h"

#include <spdlog/spdlog.h>

#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/json.hpp>
#include <ostream>

#include "app/daemon_notices.h"
#include "app/store_service.h"
#include "app/stored_overrides.h"
#include "config/config.h"
#include "web/server/on_board.h"
#include "web/server/web_server.h"

namespace xr::app {

namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;

// The daemon's own listen address, seen from this machine: a wildcard
// address is reached on loopback.
std::string localAddress(const std::string& listen) {
  if (listen == "0.0.0.0" || listen.empty()) return "127.0.0.1";
  if (listen == "::") return "::1";
  return listen;
}

}  // namespace

int pairMain(const std::optional<std::string>& configPath, const std::optional<std::string>& stateDb,
             const std::optional<std::string>& httpAddr, std::ostream& out, std::ostream& err) {
  web::WebServerOptions opts;
  std::string db = stateDb.value_or("");
  if (configPath) {
    const LoadResult r = loadConfigFile(*configPath);
    if (!r.ok()) {
      for (const auto& e : r.errors) err << e.toString() << "\n";
      return 1;
    }
    opts = web::WebServerOptions::fromSettings(r.config->settings.web, r.config->settings.web.token);
    if (db.empty()) db = r.config->settings.store.path;
  }
  if (httpAddr && !web::parseListenAddress(*httpAddr, opts)) {
    err << "xregulatord: --http: expected ADDR:PORT, got '" << *httpAddr << "'\n";
    return 1;
  }
  if (opts.token.empty()) {
    std::string why;
    opts.token = readTokenReadOnly(db, &why);
    if (opts.token.empty()) {
      err << "xregulatord: --pair: no write token: " << (why.empty() ? db + ": none stored yet" : why)
          << "\n";
      return 1;
    }
  }
  try {
    asio::io_context ioc;
    beast::tcp_stream stream(ioc);
    stream.expires_after(std::chrono::seconds(10));
    const auto address = asio::ip::make_address(localAddress(opts.listen));
    stream.connect(asio::ip::tcp::endpoint(address, opts.port));
    http::request<http::string_body> req{http::verb::post, "/api/pair/code", 11};
    req.set(http::field::host, "localhost");
    req.set(http::field::authorization, "Bearer " + opts.token);
    req.prepare_payload();
    http::write(stream, req);
    beast::flat_buffer buf;
    http::response<http::string_body> res;
    http::read(stream, buf, res);
    if (res.result() != http::status::ok) {
      err << "xregulatord: --pair: the daemon answered " << res.result_int() << ": " << res.body() << "\n";
      return 1;
    }
    const auto j = boost::json::parse(res.body()).as_object();
    out << "pairing code " << j.at("code").as_string().c_str() << " (single use, valid "
        << j.at("expires_in_s").to_number<long>() / 60 << " min): enter it on the dashboard\n";
    return 0;
  } catch (const std::exception& e) {
    err << "xregulatord: --pair: cannot reach the daemon on " << web::hostPortText(opts.listen, opts.port)
        << ": " << e.what() << "\n";
    return 1;
  }
}

}  // namespace xr::app

namespace xr::app {

void startPairing(web::WebServer& server, const StoreService* store) {
  logPairingCode(server.newPairingCode());
  if (!store) return;  // no database: no way to tell a first start
  const OpenResult& o = store->openResult();
  // Created at this start, not restored or reset after damage: a damaged
  // card must not hand the regulator to whoever pairs first.
  if (!o.ok || o.alarm() || o.fromVersion != 0) return;
  server.openFirstStartPairingWindow(kFirstStartWindowMs);
  if (server.pairingWindowOpen())
    spdlog::warn(
        "pairing: a new regulator with nothing paired: for {} min the first device to pair needs no code "
        "and becomes the owner, if it is on board: loopback, link-local or the board's own subnets ({}) "
        "(docs/security.md)",
        kFirstStartWindowMs / 60000, web::subnetsText(web::boardSubnets()));
}

}  // namespace xr::app

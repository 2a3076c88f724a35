#pragma once
// ApiHandler: one HTTP request in, one response out. No sockets here, so the
// API tests, the fuzz target and the Beast sessions share exactly this code.
// Thread-safe: the server's Asio threads call handle() concurrently.
#include <atomic>
#include <boost/asio/ip/address.hpp>
#include <boost/beast/http.hpp>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "web/server/daemon_api.h"
#include "web/server/pairing.h"
#include "web/server/web_server.h"

namespace xr::web {

namespace http = boost::beast::http;
using Request = http::request<http::string_body>;
using Response = http::response<http::string_body>;

class ApiHandler {
 public:
  ApiHandler(DaemonApi& api, const WebServerOptions& opts, std::function<WebServerStats()> stats = {});

  // peer: the client's address (the server always gives it). Without it a
  // request is not "on board": no code-less pairing (on_board.h).
  using Peer = std::optional<boost::asio::ip::address>;
  Response handle(const Request& req, const Peer& peer = std::nullopt);

  // The latest status serialised once per telemetry sequence number, shared by
  // GET /api/status and every WebSocket client. nullptr before the first tick.
  std::shared_ptr<const std::string> statusText(std::uint64_t* seqOut = nullptr);

  // Authorisation for a read (GET, /ws): Ok when reads are open.
  // Returns 0 when allowed, else 401/403.
  // A paired device's token counts like the static token.
  unsigned checkRead(std::string_view authorization, std::string_view queryToken) const;
  // Authorisation for a write: the static or a device token in the
  // Authorization header (never ?token=). 0, 401 or 403.
  unsigned checkWrite(std::string_view authorization) const;

  Pairing& pairing() { return pairing_; }

 private:
  Response route(const Request& req, const Peer& peer);
  Response getStatus(const Request& req);
  Response getParams(const Request& req);
  Response patchParams(const Request& req);
  Response postCommand(const Request& req);
  Response postDvcc(const Request& req);  // api_commands.cpp
  Response getEvents(const Request& req, std::string_view query);
  Response getHistory(const Request& req, std::string_view query);
  Response getHistoryDays(const Request& req, std::string_view query);
  Response getHistoryCharges(const Request& req, std::string_view query);
  Response getHistoryTrends(const Request& req, std::string_view query);  // api_trends.cpp
  Response getHistoryExport(const Request& req, std::string_view query);
  Response getSystem(const Request& req);
  Response getCommands(const Request& req);
  Response getMetrics(const Request& req);
  Response getHealth(const Request& req);
  Response getStatic(const Request& req, std::string_view path);
  Response getHardwareSetup(const Request& req);  // api_setup.cpp
  Response putHardwareSetup(const Request& req);
  Response pairRoutes(const Request& req, std::string_view path, const Peer& peer);
  // Who an authorised write comes from, for the event it makes: the paired
  // device's name, or the static token.
  std::string writerName(std::string_view authorization) const;
  Pairing::Caller callerOf(std::string_view authorization) const;
  Response postPair(const Request& req, const Peer& peer);
  Response postQrCode(const Request& req);
  // A code-less pairing from off the boat's networks: the reason, "" when on board.
  std::string offBoardRefusal(const Peer& peer);
  Response listDevices(const Request& req);
  Response revokeDevice(const Request& req, const std::string& id);
  Response revokeAllDevices(const Request& req);

  DaemonApi& api_;
  const WebServerOptions& opts_;
  std::function<WebServerStats()> stats_;
  Pairing pairing_;
  std::atomic<int> offBoardEvents_{0};  // refusals put in the event list (bounded)

  std::mutex cacheMutex_;
  std::uint64_t cachedSeq_ = 0;
  std::shared_ptr<const std::string> cached_;
};

// Helpers shared with the server and the tests.
std::string percentDecode(std::string_view s, bool* ok = nullptr);
// Value of `key` in a query string "a=1&b=2" (decoded); nullopt when absent.
std::optional<std::string> queryParam(std::string_view query, std::string_view key);

}  // namespace xr::web

#pragma once
// WebServer: Boost.Beast HTTP + WebSocket server on its own Asio threads.
//
// Usage (daemon/app or daemon/runtime):
//
//   auto opts = xr::web::WebServerOptions::fromSettings(config.settings.web, token);
//   // --http ADDR:PORT overrides: xr::web::parseListenAddress("127.0.0.1:8080", opts);
//   xr::web::WebServer server(api, opts);   // api: your DaemonApi implementation
//   server.start();                         // binds (throws std::runtime_error on failure)
//   ...                                     // server.port() = the bound port
//   server.stop();                          // also done by the destructor
//
// The server never calls into the control thread: it only calls DaemonApi,
// whose methods are non-blocking hand-offs (see daemon_api.h).
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "config/settings.h"
#include "web/server/daemon_api.h"
#include "web/server/pairing.h"

namespace xr::web {

struct WebServerOptions {
  std::string listen = "127.0.0.1";  // address to bind
  std::uint16_t port = 8080;         // 0 = ephemeral (tests); see WebServer::port()
  std::string token;                 // Bearer token for writes; must not be empty
  double telemetry_rate_hz = 10.0;   // WebSocket rate, clamped to [0.2, 20]
  bool reads_require_token = false;  // true: GETs and /ws need the token too
  int max_connections = 64;          // HTTP + WebSocket, over it: 503 and close
  // Per-client bounds (docs/security.md): one address holds at most
  // max_per_ip connections (0: 3/4 of max_connections) and max_ws_per_ip
  // WebSockets (0: max_connections / 4); WebSockets together leave
  // max_connections / 8 slots (at least 1) for plain requests such as /healthz.
  int max_per_ip = 0;
  int max_ws_per_ip = 0;
  std::string www_root;  // static dashboard files; empty = no static files
  int threads = 2;       // Asio threads
  std::size_t body_limit = 64 * 1024;
  std::size_t header_limit = 8 * 1024;
  std::chrono::milliseconds request_timeout{10000};    // whole request read / response write
  std::chrono::milliseconds keepalive_timeout{10000};  // idle keep-alive (docs/dashboard.md)
  // At max_connections, a new connection closes the connection that has
  // waited longest for its request, once it has waited this long: clients
  // dripping their headers cannot hold every slot (docs/security.md).
  std::chrono::milliseconds evict_waiting_after{2000};
  std::chrono::milliseconds ws_idle_timeout{30000};  // no pong within this: close
  // A frame the client does not take within this (it never reads): close.
  std::chrono::milliseconds ws_write_timeout{10000};
  // Kernel send buffer of each WebSocket: bounds what a slow client can hold
  // in the kernel, as the one-pending-frame rule bounds it in the server.
  int ws_send_buffer = 64 * 1024;
  std::vector<std::string> allowed_origins;  // extra Origins allowed on /ws and writes (same host always ok)
  // Extra names the dashboard may be reached by (Host header); IP literals,
  // localhost and this machine's hostname (also with .local) always are.
  std::vector<std::string> allowed_hosts;
  // Paired devices' token hashes (pairing.h); null: kept in memory only.
  std::shared_ptr<AuthStore> auth_store;

  static WebServerOptions fromSettings(const WebSettings& s, std::string token);
};

// Parses "ADDR:PORT" (IPv4, "[v6]:port" or ":PORT") into opts.listen/opts.port.
// Returns false (opts untouched) when malformed.
bool parseListenAddress(const std::string& text, WebServerOptions& opts);

// 32 random bytes from /dev/urandom as 64 hex characters: the token generated
// at first start when [web] token is empty (the caller stores it with the state
// and logs it once).
std::string generateToken();

// Where the dashboard assets are when [web] www_root is empty: the installed
// path (/usr/share/xregulator/www) if it exists, else the build tree's copy.
std::string defaultWwwRoot();

// Counters exported on /metrics (and readable by tests).
struct WebServerStats {
  std::uint64_t http_requests = 0;
  std::uint64_t http_errors = 0;  // 4xx + 5xx responses
  std::uint64_t ws_clients = 0;   // connected now
  std::uint64_t ws_frames_sent = 0;
  std::uint64_t ws_frames_dropped = 0;  // replaced by a newer snapshot before sending
  std::uint64_t connections = 0;        // open now
  std::uint64_t connections_refused = 0;
  std::uint64_t connections_evicted = 0;  // closed while reading a request, to make room
};

class WebServer {
 public:
  WebServer(DaemonApi& api, WebServerOptions opts);
  ~WebServer();
  WebServer(const WebServer&) = delete;
  WebServer& operator=(const WebServer&) = delete;

  void start();
  void stop();
  std::uint16_t port() const;
  WebServerStats stats() const;
  // A new single-use pairing code (pairing.h), e.g. for the journal at start.
  Pairing::Code newPairingCode();
  // A new regulator with nothing paired: the first device pairs without a
  // code for this long (pairing.h).
  void openFirstStartPairingWindow(std::int64_t durationMs);
  void openPresencePairingWindow(std::int64_t durationMs);
  bool pairingWindowOpen();

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace xr::web

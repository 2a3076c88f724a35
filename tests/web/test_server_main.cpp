// xr_web_testserver: the web server with the fake DaemonApi, publishing a
// synthetic tick every 100 ms. For the browser tests and for trying the
// dashboard without a daemon:
//   xr_web_testserver --www web/www --port 0 --token T   (prints "LISTENING <port>")
#include <csignal>
#include <cstdio>
#include <cstring>
#include <string>
#include <thread>

#include "tests/web/fake_daemon_api.h"
#include "web/server/web_server.h"

int main(int argc, char** argv) {
  xr::web::WebServerOptions o;
  o.port = 0;
  o.token = "test-token";
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i], v = argv[i + 1];
    if (k == "--port")
      o.port = static_cast<std::uint16_t>(std::stoi(v));
    else if (k == "--www")
      o.www_root = v;
    else if (k == "--token")
      o.token = v;
    else if (k == "--rate")
      o.telemetry_rate_hz = std::stod(v);
    else {
      std::fprintf(stderr, "unknown option %s\n", k.c_str());
      return 2;
    }
  }
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGTERM);
  sigaddset(&set, SIGINT);
  pthread_sigmask(SIG_BLOCK, &set, nullptr);  // before any thread starts

  xr::web::test::FakeDaemonApi api;
  api.publish();
  xr::web::WebServer server(api, o);
  server.start();
  std::printf("LISTENING %u\n", server.port());
  std::fflush(stdout);
  std::atomic<bool> run{true};
  std::thread ticker([&] {
    while (run) {
      api.publish();
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  });
  int sig = 0;
  sigwait(&set, &sig);
  run = false;
  ticker.join();
  server.stop();
  return 0;
}

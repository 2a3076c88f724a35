// Google Benchmark: the per-tick serialisation shared by every WebSocket client
// and the per-request cost of GET /api/status and GET /api/params.
#include <benchmark/benchmark.h>

#include "tests/web/fake_daemon_api.h"
#include "web/server/api_handler.h"
#include "web/server/json_format.h"

namespace {
using namespace xr::web;

void BM_SerializeStatus(benchmark::State& state) {
  test::FakeDaemonApi api;
  api.publish();
  StatusSnapshot s;
  api.latestStatus(s);
  std::size_t bytes = 0;
  for (auto _ : state) {
    auto text = serializeStatus(s);
    bytes = text.size();
    benchmark::DoNotOptimize(text);
  }
  state.counters["bytes"] = static_cast<double>(bytes);
}
BENCHMARK(BM_SerializeStatus);

void BM_HandleGetStatusCached(benchmark::State& state) {
  test::FakeDaemonApi api;
  api.publish();
  WebServerOptions o;
  o.token = "t";
  ApiHandler h(api, o);
  Request req{http::verb::get, "/api/status", 11};
  for (auto _ : state) benchmark::DoNotOptimize(h.handle(req));
}
BENCHMARK(BM_HandleGetStatusCached);

void BM_HandleGetParams(benchmark::State& state) {
  test::FakeDaemonApi api;
  WebServerOptions o;
  o.token = "t";
  ApiHandler h(api, o);
  Request req{http::verb::get, "/api/params", 11};
  for (auto _ : state) benchmark::DoNotOptimize(h.handle(req));
}
BENCHMARK(BM_HandleGetParams);

}  // namespace

BENCHMARK_MAIN();

// Helper of store_crash_test: opens the database, restores the ledger and
// then checkpoints a monotonically growing ledger (plus history and events)
// as fast as it can, writing "C <ChargedEnergy_AllTime>" to stdout after each
// checkpoint returned. The test kills it with SIGKILL at random moments.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "store/store.h"

namespace {
void say(const std::string& s) {
  const std::string line = s + "\n";
  const ssize_t n = write(STDOUT_FILENO, line.data(), line.size());
  (void)n;
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return 2;
  xr::StoreOptions opt;
  opt.historyFlushS = 5;  // flush often: more write traffic to interrupt
  xr::Store store(opt);
  std::int64_t now = 1'700'000'000'000;
  const xr::OpenResult r = store.open(argv[1], now);
  if (!r.ok) {
    say("E open " + r.message);
    return 3;
  }
  xr::BatteryLedger l;
  if (auto saved = store.loadLedger()) {
    l = saved->ledger;
    now = std::max(now, saved->savedAtMs + 1000);
  }
  char buf[64];
  std::snprintf(buf, sizeof buf, "R %.17g", l.ChargedEnergy_AllTime_Wh);
  say(buf);
  std::vector<double> sample(opt.historySeries.size(), 13.2);
  for (long i = 0;; ++i) {
    l.ChargedEnergy_AllTime_Wh += 1.0;
    l.AlternatorChargedEnergy_AllTime_Wh += 0.5;
    l.totalSocSampleTime_AllTime += 1.0;
    l.CoulombCount_Ah = std::fmod(l.ChargedEnergy_AllTime_Wh, 200.0);
    now += 1000;
    store.appendHistory(now, sample);
    if (i % 7 == 0) {
      xr::EventRecord e{0, now, "Info", "Message", "NONE", "tick " + std::to_string(i), 1.0, 2.0};
      store.appendEvents(std::span<const xr::EventRecord>(&e, 1));
    }
    const xr::StoreStatus s = store.checkpoint(l, "interval", now);
    if (!s.ok) {
      say("E checkpoint " + s.error);
      return 4;
    }
    std::snprintf(buf, sizeof buf, "C %.17g", l.ChargedEnergy_AllTime_Wh);
    say(buf);
  }
}

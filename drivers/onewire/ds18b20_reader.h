#pragma once
// DS18B20 reader (docs/install.md, wiring): a non-RT thread reads
// <root>/<id>/w1_slave at 1 Hz and publishes {tempF, stamp} plus a
// heartbeat through a SeqLock (lock-free) for the control thread:
// Inputs::AlternatorTemperatureF (T5 needs the stamps) and
// Inputs::tempTaskHeartbeat (T4: the temperature task is alive).
#include <atomic>
#include <functional>
#include <string>
#include <thread>

#include "core/seqlock.h"
#include "core/time.h"
#include "drivers/onewire/w1_therm.h"

namespace xr {

struct Ds18b20Sample {
  double tempF = 0.0;
  TimeNs stamp = 0;        // monotonic time of the last accepted reading (0 = never)
  TimeNs heartbeat = 0;    // monotonic time the thread last completed a cycle
  std::uint32_t good = 0;  // accepted readings
  std::uint32_t bad = 0;   // rejected (CRC NO, 85000, malformed, missing)
  w1::ParseError lastError = w1::ParseError::None;
  bool sensorFound = false;
};

class Ds18b20Reader {
 public:
  using NowFn = std::function<TimeNs()>;
  // `sensorId` "28-..." or empty for the first one found under `root`.
  // `now` defaults to CLOCK_MONOTONIC.
  Ds18b20Reader(std::string root, std::string sensorId, TimeNs period = 1'000'000'000, NowFn now = {});
  ~Ds18b20Reader();
  Ds18b20Reader(const Ds18b20Reader&) = delete;
  Ds18b20Reader& operator=(const Ds18b20Reader&) = delete;

  // With an empty sensorId, "the first one found" skips this id (the battery
  // sensor on the same bus).
  void excludeId(std::string id) { exclude_ = std::move(id); }

  // Called on the reader's thread with each cycle's sample, after latest()
  // has it: the consumer's own hand-off is written once, by this thread.
  // Set before start().
  using Sink = std::function<void(const Ds18b20Sample&)>;
  void onSample(Sink sink) { sink_ = std::move(sink); }

  void start();
  void stop() noexcept;
  // One read cycle (what the thread does each period); public for tests.
  void readOnce();
  // RT-safe: the newest published sample.
  Ds18b20Sample latest() const noexcept { return out_.load(); }
  const std::string& sensorPath() const noexcept { return path_; }

 private:
  void run();
  // One reading from the held descriptor: -1 on a read error, else bytes.
  static long readSlave(int fd, char* buf, std::size_t cap) noexcept;
  void closeSlave() noexcept;
  std::string root_;
  std::string id_;
  std::string exclude_;
  std::string path_;
  int fd_ = -1;  // w1_slave, held open between readings
  TimeNs period_;
  NowFn now_;
  Ds18b20Sample state_;
  SeqLock<Ds18b20Sample> out_;
  Sink sink_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace xr

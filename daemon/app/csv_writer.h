#pragma once
// Telemetry CSV (--telemetry-csv): one header row, then one row per
// telemetry row the control cycle queued at --telemetry-rate. Columns: the
// The CSV columns (docs/operations.md) through visitTelemetryColumns(), then in simulation the
// plant's truth (sim_*). Written by its own non-RT thread.
#include <atomic>
#include <cstdio>
#include <string>
#include <thread>

#include "runtime/handoffs.h"

namespace xr::app {

class CsvWriter {
 public:
  // Throws std::runtime_error when the file cannot be created.
  CsvWriter(const std::string& path, rt::Handoffs& h, bool simColumns);
  ~CsvWriter();
  void start();
  // Drains every queued row, flushes and closes.
  void stop();
  std::uint64_t rows() const { return rows_.load(); }

  // One number as a plain decimal (no exponent; NaN/inf as empty).
  static std::string formatNumber(double v);
  static std::string header(bool simColumns);
  static std::string row(const rt::RuntimeSnapshot& s, bool simColumns);

 private:
  void run();
  std::size_t drain();
  std::FILE* f_ = nullptr;
  rt::Handoffs& h_;
  bool sim_;
  std::atomic<bool> stop_{false};
  std::atomic<std::uint64_t> rows_{0};
  std::thread thread_;
};

}  // namespace xr::app

#include "app/csv_writer.h"

#include <fmt/format.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <variant>

#include "app/thread_names.h"

namespace xr::app {

namespace {
template <typename... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
template <typename... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;
}  // namespace

std::string CsvWriter::formatNumber(double v) {
  if (!std::isfinite(v)) return {};
  std::string s = fmt::format("{:.6f}", v);
  // Trim trailing zeros (and a bare point): 14.400000 -> 14.4, 3.000000 -> 3
  const auto dot = s.find('.');
  if (dot != std::string::npos) {
    while (!s.empty() && s.back() == '0') s.pop_back();
    if (!s.empty() && s.back() == '.') s.pop_back();
  }
  if (s == "-0") s = "0";
  return s;
}

std::string CsvWriter::header(bool simColumns) {
  std::string out;
  visitTelemetryColumns(Telemetry{}, 0, [&](std::string_view name, const ColumnValue&) {
    if (!out.empty()) out += ',';
    out += name;
  });
  if (simColumns) out += ",sim_battery_v,sim_alt_a,sim_alt_temp_f,sim_soc_pct,sim_bms_connected,sim_field_on";
  return out + '\n';
}

std::string CsvWriter::row(const rt::RuntimeSnapshot& s, bool simColumns) {
  std::string out;
  bool first = true;
  visitTelemetryColumns(s.telemetry, s.start, [&](std::string_view, const ColumnValue& v) {
    if (!first) out += ',';
    first = false;
    std::visit(Overloaded{[&](double d) { out += formatNumber(d); }, [&](bool b) { out += b ? '1' : '0'; },
                          [&](std::string_view n) { out += n; }},
               v);
  });
  if (simColumns) {
    const rt::SimTruth& t = s.sim;
    out += ',' + formatNumber(t.sim_battery_v) + ',' + formatNumber(t.sim_alt_a) + ',' +
           formatNumber(t.sim_alt_temp_f) + ',' + formatNumber(t.sim_soc_pct) + ',' +
           (t.sim_bms_connected ? '1' : '0') + ',' + (t.sim_field_on ? '1' : '0');
  }
  return out + '\n';
}

CsvWriter::CsvWriter(const std::string& path, rt::Handoffs& h, bool simColumns) : h_(h), sim_(simColumns) {
  f_ = std::fopen(path.c_str(), "w");
  if (!f_) throw std::runtime_error("cannot create telemetry CSV " + path + ": " + std::strerror(errno));
  const std::string hdr = header(sim_);
  std::fwrite(hdr.data(), 1, hdr.size(), f_);
}

CsvWriter::~CsvWriter() { stop(); }

void CsvWriter::start() {
  thread_ = std::thread([this] {
    nameThisThread("xr-csv");
    run();
  });
}

std::size_t CsvWriter::drain() {
  std::size_t n = 0;
  rt::RuntimeSnapshot s;
  while (h_.rows.pop(s)) {
    const std::string line = row(s, sim_);
    std::fwrite(line.data(), 1, line.size(), f_);
    ++n;
  }
  rows_ += n;
  return n;
}

void CsvWriter::run() {
  while (!stop_.load()) {
    if (drain() == 0) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

void CsvWriter::stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
  if (f_) {
    drain();
    std::fclose(f_);
    f_ = nullptr;
  }
}

}  // namespace xr::app

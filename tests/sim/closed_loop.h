#pragma once
// Helpers for the closed-loop scenario tests: run an inline scenario through
// the whole loop (real drivers + runtime + regulator on the simulated world)
// and query the rows.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>
#include <string>

#include "sim_rig/sim_runner.h"

namespace xr::sim::test {

// The battery's health over simulated days (capacity, resistance, SoC) runs
// its loop at 100 Hz instead of the shipped 400 Hz: those figures work on
// one-second means and came out the same at both rates, in about a third of
// the time (docs/development.md "make test's time").
inline constexpr int kHealthDaysControlPeriodUs = 10000;

inline SimRunResult runText(const std::string& toml, double rateHz = 2.0) {
  SimRunOptions o;
  o.scenario = parseScenario(toml, "inline.toml");
  o.telemetryRateHz = rateHz;
  SimRunner r(o);
  SimRunResult res = r.run();
  // Every run: the drivers never sent anything the chips refuse, and the
  // field is safe when the run ends.
  EXPECT_EQ(res.inaProtocolErrors, 0u);
  EXPECT_EQ(res.adsProtocolErrors, 0u);
  EXPECT_FALSE(res.finalFieldEnable);
  EXPECT_EQ(res.finalDuty, 0.0);
  return res;
}

// First row at or after t (seconds); nullptr if none.
inline const SimRow* at(const SimRunResult& r, double t) {
  for (const auto& row : r.rows)
    if (row.t_s >= t - 1e-9) return &row;
  return nullptr;
}

// First time pred holds (at or after `from`), or -1.
inline double firstTime(const SimRunResult& r, const std::function<bool(const SimRow&)>& pred,
                        double from = 0.0) {
  for (const auto& row : r.rows)
    if (row.t_s >= from && pred(row)) return row.t_s;
  return -1.0;
}

inline double maxOf(const SimRunResult& r, const std::function<double(const SimRow&)>& f, double from = 0.0,
                    double to = 1e18) {
  double m = -1e18;
  for (const auto& row : r.rows)
    if (row.t_s >= from && row.t_s <= to) m = std::max(m, f(row));
  return m;
}

inline bool all(const SimRunResult& r, const std::function<bool(const SimRow&)>& pred, double from = 0.0,
                double to = 1e18) {
  for (const auto& row : r.rows)
    if (row.t_s >= from && row.t_s <= to && !pred(row)) return false;
  return true;
}

// A compact trace for failure messages.
inline std::string trace(const SimRunResult& r, double every = 30.0) {
  std::ostringstream os;
  double next = 0;
  for (const auto& row : r.rows) {
    if (row.t_s < next) continue;
    next = row.t_s + every;
    const auto& t = row.telemetry;
    os << row.t_s << "s " << toString(t.mode) << ' ' << toString(t.stage) << ' ' << toString(t.reason)
       << " ibv=" << t.ibv_v << " bcur=" << t.bcur_a << " alt=" << t.alt_a << " duty=" << t.duty_pct
       << " en=" << t.field_enable << " soc=" << t.soc_pct << " tF=" << t.temp_f
       << " pen=" << t.thermal_penalty_a << " | V=" << row.plant.battery_v << " Ib=" << row.plant.battery_a
       << " Ia=" << row.plant.alt_a << " T=" << row.plant.alt_temp_f << " soc=" << row.plant.soc_pct << '\n';
  }
  return os.str();
}

}  // namespace xr::sim::test

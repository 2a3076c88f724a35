#pragma once
// Day-by-day and charge-by-charge summaries for the History page
// (docs/dashboard.md "History"): what an owner compares across a passage —
// amp-hours and watt-hours the alternator gave, hours in each stage, the
// hottest the alternator got, and for each charge how long it took, what it
// delivered and why it ended. Pure: one sample a second in, summaries out;
// the store keeps them (store_history_days.cpp).
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>

#include "core/charge_summaries.h"
#include "core/modes.h"

namespace xr {

struct TallySample {
  std::int64_t unixMs = 0;
  std::string day;  // local calendar day, "YYYY-MM-DD"
  double altA = NAN, batteryV = NAN, batteryA = NAN, altTempC = NAN, socPct = NAN;  // NaN: not known
  ChargeStage stage = ChargeStage::BULK;
  bool fieldOn = false;
  bool engineRunning = false;
  Reason reason = Reason::NONE;
};

// A charge is one stretch of field-on time; a field off shorter than this
// (a protection's cooldown, a stop at a lock) does not end it.
inline constexpr std::int64_t kChargeGapMs = 5 * 60 * 1000;
// A gap between samples longer than this (the daemon stopped, the clock
// jumped) is not integrated: nothing is known about it.
inline constexpr double kTallyMaxStepS = 5.0;

class ChargeTally {
 public:
  struct Ended {
    std::optional<DaySummary> day;        // a day that ended with this sample
    std::optional<ChargeSummary> charge;  // a charge that ended with it
  };
  // Today's totals saved by an earlier run (a restart keeps counting).
  void restoreDay(const DaySummary& d) { day_ = d; }
  Ended add(const TallySample& s);
  const DaySummary& day() const { return day_; }
  const std::optional<ChargeSummary>& charge() const { return charge_; }
  // The longest step integrated (kTallyMaxStepS by default): a simulated
  // clock read once a wall second moves by --speed seconds at a time.
  void setMaxStepS(double s) { maxStepS_ = s; }
  // The store gave the open charge its row id.
  void setChargeId(std::int64_t id) {
    if (charge_) charge_->id = id;
  }

 private:
  void addToDay(const TallySample& s, double dt);
  std::optional<ChargeSummary> addToCharge(const TallySample& s, double dt);

  DaySummary day_;
  double maxStepS_ = kTallyMaxStepS;
  std::optional<ChargeSummary> charge_;
  std::optional<std::int64_t> fieldOffSinceMs_;
  Reason offReason_ = Reason::NONE;
  std::optional<std::int64_t> lastMs_;
};

}  // namespace xr

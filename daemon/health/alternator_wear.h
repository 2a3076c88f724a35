#pragma once
// AlternatorWear: running time, time at or above each band of the measured
// temperature, and the share of the windings' insulation life used
// (docs/operations.md "Alternator wear"). Pure: time comes in as dt.
//
// Insulation life: a thermal class is the temperature at which the
// insulation lasts kClassLifeHours (docs/sources.md W1), and the life halves
// for every kHalvingC above it and doubles for every kHalvingC below (the
// Arrhenius rule of thumb, W2). One hour at temperature T uses
// 2^((T - Tclass) / kHalvingC) / kClassLifeHours of the life.
#include <array>

#include "battery/ledger.h"
#include "params/params.h"

namespace xr {

namespace wear_k {
inline constexpr double kClassLifeHours = 20000.0;
inline constexpr double kHalvingC = 10.0;
// B, F, H (AltInsulationClass 0, 1, 2).
inline constexpr double kClassC[] = {130.0, 155.0, 180.0};
// The current's share of AltRatedCurrent_A is capped here for the winding rise.
inline constexpr double kMaxLoadShare = 1.5;
}  // namespace wear_k

// The wear figures exported per tick (hours, %, a count).
struct WearTelemetry {
  double alt_run_hours = 0.0;
  std::array<double, kWearBandsF.size()> alt_hours_above{};  // at or above kWearBandsF
  double alt_life_used_pct = 0.0;
  double belt_slip_events = 0.0;
  bool belt_slipping = false;  // an episode is under way
};

class AlternatorWear {
 public:
  // Every tick: dt, whether the alternator turns, the measured temperature
  // (degF, NaN when unknown: no band or life counted) and its current.
  void update(double dt_s, bool running, double sensorF, double altAmps, const Params& p) noexcept;
  // The winding temperature estimate, degC.
  static double windingC(double sensorF, double altAmps, const Params& p) noexcept;
  // Share of the life (0..1) one hour at windingC uses for an insulation class.
  static double lifePerHour(double windingC, int insulationClass) noexcept;
  void countBeltSlip() noexcept { l_.BeltSlipEvents += 1.0; }

  void fillTelemetry(WearTelemetry& t) const noexcept;
  const AlternatorWearLedger& ledger() const noexcept { return l_; }
  void restore(const AlternatorWearLedger& l) noexcept;

 private:
  AlternatorWearLedger l_;
};

}  // namespace xr

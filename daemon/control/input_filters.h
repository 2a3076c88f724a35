#pragma once
// The control law's feedback filters and tick timing (docs/control.md
// "Feedback filters"): one update() per tick over the corrected sensors.
// Every later part reads the filtered values from here.
#include "control/control_sensors.h"
#include "control/feedback_filters.h"
#include "params/params.h"

namespace xr {

class InputFilters {
 public:
  // Every tick, first: the filters on fresh CH1 / IBV and both dts.
  void update(const ControlSensors& s, const Params& p) noexcept;

  double tickDt() const noexcept { return tickDt_; }
  double controlDt() const noexcept { return controlDt_; }
  TimeNs lastTick() const noexcept { return lastTick_; }
  double measuredAmps() const noexcept { return MeasuredAmps_; }
  double pidSignal() const noexcept { return pidSig_; }
  const Ema& input() const noexcept { return emaInput_; }
  const Ema& pidFiltered() const noexcept { return emaPid_; }
  const Ema& ibvFiltered() const noexcept { return emaIBV_; }
  const Ema& bcurSlow() const noexcept { return emaBcur_; }
  double pidMovingAverage() const noexcept { return maPid_.value(); }
  double ibvSlope() const noexcept { return ibvSlope_; }

  // A control dt longer than this is not integrated as-is: such a gap means
  // the sensor stalled (current-stale protection acts on it); integrating it
  // would kick every loop.
  static constexpr double kMaxControlDtSec = 0.25;

 private:
  static constexpr double kBcurSlowTcMs = 2000.0;

  Ema emaInput_;                 // MeasuredAmps_filtered (InputFilterTC)
  Ema emaPid_;                   // g_pidI_filtered, the PID's filtered current (OutputPIDFilterTC)
  Ema emaIBV_;                   // IBV_filtered (VoltageFilterTC), on fresh IBV only
  Ema emaBcur_;                  // battery current over seconds: what the bank accepted before a load dump
  MovingAverage<64> maPid_;      // g_pidMA_N, the PID's moving-average source (OutputPIDMA_N)
  double MeasuredAmps_ = 0.0;    // the last fresh, finite CH1 current
  double pidSig_ = 0.0;          // the PID's input signal per OutputPIDSigSrc
  TimeNs lastControlTick_ = -1;  // the last fresh CH1 (-1: none yet)
  TimeNs lastTick_ = -1;         // the last tick (-1: none yet)
  double controlDt_ = 0.0;       // seconds between fresh CH1 samples (0 on other ticks)
  double tickDt_ = 0.0;          // seconds since the last tick
  TimeNs lastFilterIbvNs_ = -1;  // the last fresh IBV sample (-1: none yet)
  double ibvSlope_ = 0.0;        // cvDSlope: dV/dt of IBV_filtered between fresh IBV samples
  double lastFiltV_ = 0.0;       // IBV_filtered at the last fresh IBV sample
};

}  // namespace xr

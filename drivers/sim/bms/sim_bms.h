#pragma once
// SimBms: a simulated LFP BMS on the CAN bus (the Victron/SMA frame set),
// driven by the plant's truth. What it sends:
//   CVL: cvlV (cells x 3.55 V: 14.2 V for 4 cells; the rig sets it from the
//        bank's cells unless the scenario's [bms] cvl_v does), or a
//        scenario's bms_cvl_v event
//   CCL: cclMaxA, tapered as the bank nears full and when cold, or a
//        scenario's bms_ccl_a. Taper by SoC after the dbus-serialbattery
//        table (85 %: 100 %, 90 %: 50 %, 95 %: 20 %, 98 %: 10 %), by
//        temperature 0 A at <= 0 degC rising to full at 10 degC (CCL 0 at
//        0 degC in the same driver); docs/sources.md P3.10.3
//   warnings: high voltage above CVL + 0.1 V, or forced (bms_warn)
// If its limits are ignored (charge current above CCL + 5 A, or any charge
// above 2 A while it warns) for openAfterS, it opens its contactor: the
// caller disconnects the plant's battery (the plant's BMS disconnect).
// `talking = false` (bms_can = "silent") stops its frames; `shortFrames`
// (bms_can = "short_frames") sends its limits (0x351) with DLC 4, which a
// decoder must reject. `pylontech` adds the 0x359 flags frame. `rec` sends
// REC's 0x355 (with the 0.01 % SoC) and 0x373: its cells are the pack
// voltage / `cells`, the highest `cellSpreadV` over that and the lowest as
// far under (an unbalanced pack), at the plant's battery temperature; a
// cell above kCellWarnV raises its high-voltage warning, as REC's own
// per-cell limit does.
#include <cstdint>
#include <vector>

#include "core/time.h"
#include "drivers/hal/can_bus.h"

namespace xr::sim {

struct SimBmsTruth {
  double batteryV = 0.0;
  double batteryA = 0.0;  // + = charging
  double socPct = 50.0;
  double tempC = 25.0;
};

class SimBms {
 public:
  double cvlV = 14.2;
  double cclMaxA = 100.0;
  double openAfterS = 3.0;
  bool talking = true;
  double forcedCclA = -1.0;  // < 0: not forced
  double forcedCvlV = -1.0;
  bool forcedWarning = false;
  bool shortFrames = false;
  bool pylontech = false;
  bool rec = false;
  int cells = 4;  // in series it is set up for (the rig: [bms] cells, else the bank's)
  double cellSpreadV = 0.0;

  // One step of `dt` seconds; returns the frames to send now (every
  // kPeriodS of simulated time while talking).
  std::vector<CanFrame> step(TimeNs now, const SimBmsTruth& t);

  double ccl(const SimBmsTruth& t) const;
  double cvl() const { return forcedCvlV > 0.0 ? forcedCvlV : cvlV; }
  bool warning(const SimBmsTruth& t) const;
  double cellMaxV(const SimBmsTruth& t) const { return t.batteryV / cells + cellSpreadV; }
  double cellMinV(const SimBmsTruth& t) const { return t.batteryV / cells - cellSpreadV; }
  bool contactorOpen() const { return open_; }
  void closeContactor() { open_ = false, ignoredSince_ = -1; }

  static constexpr double kPeriodS = 0.5;
  static constexpr double kCellWarnV = 3.65;  // LFP's usual cell maximum

 private:
  bool open_ = false;
  TimeNs ignoredSince_ = -1;
  TimeNs nextSend_ = 0;
};

}  // namespace xr::sim

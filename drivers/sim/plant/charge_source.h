#pragma once
// Another charger on the same bank (docs/simulator.md "Other charge
// sources"): a solar MPPT controller or a shore charger. Each is a current
// source with its own three stages, as such chargers have:
//   bulk:       its whole current (the sun's, or its rating) until the bus
//               reaches its absorption voltage;
//   absorption: holds that voltage until its current falls below its tail
//               or its absorption time runs out;
//   float:      holds its float voltage; back to bulk when the bus stays
//               below its re-bulk voltage for a minute (a load it cannot
//               carry), and for a solar controller every morning.
// It holds a voltage the way a real controller does, with a loop on its own
// current (it measures at its terminals, which are the bus here), so two
// chargers with different voltages settle as on a boat: the higher one
// carries the bank, the lower one gives nothing.
#include <string_view>

namespace xr::sim {

struct ChargeSourceConfig {
  bool present = false;
  bool solar = false;         // true: the current follows the day curve
  double max_a = 20.0;        // the charger's rating; solar: at noon on a clear day
  double absorption_v = 0.0;  // 0 = 14.4 V per 12 V nominal
  double float_v = 0.0;       // 0 = 13.5 V per 12 V nominal
  double rebulk_v = 0.0;      // 0 = 12.8 V per 12 V nominal
  double absorption_s = 7200.0;
  double tail_a = 0.0;  // 0 = 5 % of max_a
  // Solar: the clock at t = 0 and the day (hours, local time). The current
  // is max_a x sin(pi x (h - sunrise) / (sunset - sunrise)) in the day, 0 at night.
  double start_h = 8.0, sunrise_h = 6.0, sunset_h = 20.0;
  bool on = true;  // shore power at the start (events switch it)
};

enum class SourceStage { Off, Bulk, Absorption, Float };
std::string_view toString(SourceStage s);

class ChargeSource {
 public:
  ChargeSource(const ChargeSourceConfig& c, double nominalV);
  // The current it gives this step (A, into the bus): constant within the
  // step, moved by its own loop from the bus voltage of the last step.
  double amps() const noexcept { return amps_; }
  void step(double busV, double dt) noexcept;
  void setOn(bool on) noexcept { on_ = on; }
  bool present() const noexcept { return cfg_.present; }
  SourceStage stage() const noexcept { return stage_; }
  double availableAmps() const noexcept;  // what it could give now (sun or rating)

 private:
  ChargeSourceConfig cfg_;
  double t_ = 0.0, amps_ = 0.0, stageS_ = 0.0, lowS_ = 0.0;
  bool on_;
  SourceStage stage_ = SourceStage::Off;
};

}  // namespace xr::sim

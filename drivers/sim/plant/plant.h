#pragma once
// The physical system on the DC bus: alternator (a Lundell machine through
// its cable), battery (behind a BMS contactor), house loads (resistive at the
// nominal voltage), bus capacitance and a TVS clamp. The alternator's output
// depends on the bus voltage, so each step solves the bus node. When the BMS
// opens, only the bus capacitance, the house load and the TVS remain: the bus
// rises until the machine's own output falls (its EMF behind the stator
// impedance, its field decaying or fed by the risen bus) or the TVS clamps;
// the peak is recorded.
#include <algorithm>

#include "drivers/sim/plant/alternator.h"
#include "drivers/sim/plant/battery.h"
#include "drivers/sim/plant/charge_source.h"

namespace xr::sim {

struct PlantConfig {
  BatteryConfig battery;
  AlternatorConfig alternator;
  double rpm = 1800.0;    // engine RPM
  double house_a = 15.0;  // house load at the nominal voltage
  // A fridge compressor (docs/simulator.md "Loads"): fridge_a while it runs,
  // fridge_duty of every fridge_period_s, on top of house_a. 0 = none.
  double fridge_a = 0.0, fridge_duty = 0.5, fridge_period_s = 1800.0;
  ChargeSourceConfig solar, charger;  // [solar], [charger]
  double bus_capacitance_f = 0.01;
  double tvs_clamp_v = 0.0;  // 0 = 2.5 x nominal (30 V on a 12 V bus)
};

struct PlantTruth {
  double battery_v = 0.0;  // bus voltage at the battery terminals
  double battery_a = 0.0;  // into the battery (+ = charging)
  double alt_a = 0.0;
  double alt_terminal_v = 0.0;
  double alt_temp_f = 0.0;  // housing (where the sensor sits)
  double alt_stator_c = 0.0;
  double house_a = 0.0;    // house load and fridge
  double solar_a = 0.0;    // from the solar controller
  double charger_a = 0.0;  // from the shore charger
  double soc_pct = 0.0;
  double field = 0.0;    // field current / full field at 13.5 V, 20 °C
  double field_a = 0.0;  // field current
  double battery_temp_c = 0.0;
  bool bms_connected = true;
  double peak_bus_v = 0.0;           // highest bus voltage so far
  double peak_disconnected_v = 0.0;  // highest bus voltage while the BMS was open
};

class Plant {
 public:
  explicit Plant(const PlantConfig& c);
  // Advance by dt with the field command (duty 0..1 x effective enable).
  // Sub-steps itself while the battery is off the bus (fast dynamics).
  void step(double fieldCmd, double dt) noexcept;
  const PlantTruth& truth() const noexcept { return truth_; }

  void setRpm(double rpm) noexcept { rpm_ = rpm; }
  double rpm() const noexcept { return rpm_; }
  void setHouseAmps(double a) noexcept;
  void setAmbientF(double f) noexcept { ambientF_ = f; }
  double ambientF() const noexcept { return ambientF_; }
  void setBatteryTempC(double c) noexcept { bat_.setTempC(c); }
  void setBmsConnected(bool c) noexcept;
  void setFieldOpen(bool open) noexcept { alt_.setOpen(open); }
  // A slipping belt (docs/simulator.md "Faults"): the alternator turns
  // slower than the pulley ratio says, by `s` at its rated output and in
  // proportion to the current it gives (the belt's load) below that.
  void setBeltSlip(double s) noexcept { beltSlip_ = std::clamp(s, 0.0, 0.9); }
  // The engine rpm the alternator's speed corresponds to (what its W-terminal tach shows).
  double tachRpm() const noexcept { return rpm_ * (1.0 - slipNow_); }
  void setSocPct(double p) noexcept { bat_.setSocPct(p); }
  void setChargerOn(bool on) noexcept { charger_.setOn(on); }
  const ChargeSource& solar() const noexcept { return solar_; }
  const ChargeSource& charger() const noexcept { return charger_; }
  double tvsClampV() const noexcept { return tvs_; }
  const BatteryModel& battery() const noexcept { return bat_; }
  const AlternatorModel& alternator() const noexcept { return alt_; }

 private:
  void subStep(double fieldCmd, double dt) noexcept;
  void refreshTruth() noexcept;
  PlantConfig cfg_;
  BatteryModel bat_;
  AlternatorModel alt_;
  ChargeSource solar_, charger_;
  double rpm_;
  double t_ = 0.0;  // seconds since the start (the fridge's cycle)
  double beltSlip_ = 0.0, slipNow_ = 0.0;
  double ambientF_;
  double houseG_;           // house load conductance, S (0 = no load)
  double fridgeG_;          // the fridge's conductance while its compressor runs
  double houseNowG_ = 0.0;  // the whole load's conductance in the last step
  double tvs_;
  bool bmsConnected_ = true;
  double busV_;
  double batA_ = 0.0;
  PlantTruth truth_;
};

}  // namespace xr::sim

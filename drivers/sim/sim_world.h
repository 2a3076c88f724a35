#pragma once
// SimWorld: the whole simulated board and boat. Owns the plant, the chip
// models on a simulated I2C bus, the simulated 1-Wire tree, the simulated
// PWM/GPIO/watchdog and the virtual time. advanceTo(t) steps the plant and
// lets the chips convert on the simulated clock; the drivers above see only
// the hal seams (I2cBus, PwmOutput, DigitalOutput, DigitalInput, Watchdog)
// and the w1 sysfs directory.
//
// Board wiring modelled here (docs/simulator.md):
//   INA228 on a low-side shunt, VBUS on battery positive; its ALERT pin pulls
//   the gate-driver enable low (so BOVL cuts the field in hardware).
//   ADS1115 CH0 battery voltage divider, CH1 Hall sensor, CH2 LM2907 (2 s
//   coupling on signal loss), CH3 thermistor; scaling via drivers/frontend.
#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>

#include "config/settings.h"
#include "drivers/sim/ads1115_model.h"
#include "drivers/sim/faults.h"
#include "drivers/sim/ina228_model.h"
#include "drivers/sim/plant/plant.h"
#include "drivers/sim/prng.h"
#include "drivers/sim/sim_button.h"
#include "drivers/sim/sim_i2c_bus.h"
#include "drivers/sim/sim_onewire.h"
#include "drivers/sim/sim_outputs.h"

namespace xr::sim {

// Sensor noise, one sigma per measured quantity (0 = none), as seen in one
// reading: the ADS1115 channels draw it per conversion (RPM at the LM2907
// output, while there is a tach signal), the INA228 pins per plant step (the
// chip averages the raw samples of its window), the temperatures every 50 ms.
// Distribution: see prng.h (bounded near-Gaussian).
struct NoiseConfig {
  double ibv_v = 0.002;      // INA228 VBUS
  double bcur_a = 0.05;      // shunt current
  double battery_v = 0.005;  // CH0
  double alt_a = 0.2;        // CH1 Hall
  double rpm = 3.0;          // CH2
  double temp_f = 0.1;       // DS18B20 and thermistor
};

struct WorldConfig {
  PlantConfig plant;
  NoiseConfig noise;
  std::uint64_t seed = 1;
  // Where the simulated w1 sysfs tree lives (a temp directory); empty = no
  // 1-Wire sensor simulated.
  std::filesystem::path w1Root;
  // A second DS18B20 on that tree reading the plant's battery temperature
  // (docs/batteries.md): its w1 id, empty = none.
  std::string batteryW1Id;
  double inaDieTempC = 35.0;
  double adsClockScale = 1.0;  // ADS1115 oscillator: 1.1 = 10 % slow
  TimeNs maxStep = fromUs(2500);
};

// Plant truth plus the board-level facts, for the CSV sim_* columns.
struct SimTruth {
  PlantTruth plant;
  bool field_on = false;   // field drive reaching the winding
  bool ina_alert = false;  // INA228 ALERT active (enable pulled low)
};

class SimWorld {
 public:
  SimWorld(const WorldConfig& cfg, const HardwareSettings& hw);
  ~SimWorld();
  SimWorld(const SimWorld&) = delete;
  SimWorld& operator=(const SimWorld&) = delete;

  TimeNs now() const noexcept { return now_; }
  // Advance virtual time to t (no-op if t <= now). The plant steps on its own
  // grid (multiples of cfg.maxStep from time 0; 250 us while the BMS has the
  // battery off the bus); the chips convert up to t at any instant, between
  // grid points with the analog inputs of the last plant step (the plant
  // moves negligibly in a millisecond). So an advance to an ADS1115 ready
  // edge between two control ticks costs no plant step, and a run that only
  // advances on the grid steps exactly as it always did.
  // Inline for the common call, an advance to an ADS1115 ready edge between
  // two grid points (about two per control tick): the chips move, the plant
  // does not.
  void advanceTo(TimeNs t) noexcept {
    if (t <= now_) return;
    if (t < gridNext_ && plant_.truth().bms_connected) {
      advanceChips(t);
      return;
    }
    advanceStepping(t);
  }
  // Time of the last plant step (<= now()).
  TimeNs plantTime() const noexcept { return plantNow_; }

  // The hal seams the drivers and runtime use.
  I2cBus& i2c() noexcept { return bus_; }
  PwmOutput& pwm() noexcept { return pwm_; }
  DigitalOutput& fieldEnable() noexcept { return fieldEnable_; }
  DigitalOutput& buzzer() noexcept { return buzzer_; }
  DigitalInput& ignition() noexcept { return ignition_; }
  // BMS signal line (cycle_devices.h): 1 = the BMS asserts "charge disabled".
  DigitalInput& bmsLine() noexcept { return bmsLine_; }
  // The pairing button (sim_button.h); the daemon reads it only with [pairing] button_line set.
  SimButtonInput& pairingButton() noexcept { return pairingButton_; }
  Watchdog& watchdog() noexcept { return watchdog_; }
  const std::filesystem::path& w1Root() const noexcept { return cfg_.w1Root; }

  // Models, for tests and the runner.
  SimI2cBus& bus() noexcept { return bus_; }
  Ina228Model& ina() noexcept { return ina_; }
  Ads1115Model& ads() noexcept { return ads_; }
  SimOneWire* onewire() noexcept { return w1_.get(); }
  SimOneWire* batteryOnewire() noexcept { return batteryW1_.get(); }
  Plant& plant() noexcept { return plant_; }
  SimPwm& simPwm() noexcept { return pwm_; }
  SimDigitalOutput& simFieldEnable() noexcept { return fieldEnable_; }
  SimDigitalOutput& simBuzzer() noexcept { return buzzer_; }
  SimWatchdog& simWatchdog() noexcept { return watchdog_; }

  // Scenario controls.
  void setIgnition(bool on) noexcept { ignition_.setLevel(on); }
  void setPairingButton(bool pressed) { pairingButton_.setPressed(pressed, now_); }
  void setBmsChargeEnabled(bool en) noexcept;
  void setFault(Fault f, bool active, double value = 0.0);
  bool faultActive(Fault f) const noexcept { return faults_[int(f)]; }
  double faultValue(Fault f) const noexcept { return faultValues_[int(f)]; }

  SimTruth truth() const noexcept;
  bool fieldGateEnabled() const noexcept;

 private:
  void advanceStepping(TimeNs t) noexcept;  // advanceTo() with a plant step due by t
  // Between grid points: only the chips move, on the last plant step's inputs.
  void advanceChips(TimeNs t) noexcept {
    now_ = t;
    ina_.update(t);
    ads_.update(t);
  }
  void refreshAnalog(double dt) noexcept;
  void stepPlant(TimeNs to) noexcept;
  double fieldCommand() const noexcept;

  WorldConfig cfg_;
  HardwareSettings hw_;
  TimeNs now_ = 0;
  TimeNs plantNow_ = 0;
  TimeNs grid_;      // cfg.maxStep, at least 1 us
  TimeNs gridNext_;  // the first multiple of grid_ after plantNow_
  // Linear front-end scalings (frontend::adcFrom*, same arithmetic), hoisted
  // out of the per-step path.
  double ch0Gain_ = 1.0;   // battery volts per ADC volt
  double rpmScale_ = 1.0;  // engine RPM per ADC volt
  Rng rng_;
  Plant plant_;
  SimI2cBus bus_;
  Ina228Model ina_;
  Ads1115Model ads_;
  std::unique_ptr<SimOneWire> w1_;
  std::unique_ptr<SimOneWire> batteryW1_;
  SimPwm pwm_;
  SimDigitalOutput fieldEnable_;
  SimDigitalOutput buzzer_;
  SimDigitalInput ignition_;
  SimDigitalInput bmsLine_{false};
  SimButtonInput pairingButton_;
  SimWatchdog watchdog_;
  std::array<bool, kFaultCount> faults_{};
  std::array<double, kFaultCount> faultValues_{};
  std::array<double, 4> pinSigma_{};  // ADS1115 noise per conversion, ADC volts (without faults)
  double lm2907V_ = 0.0;
  // Slow channels (temperatures) are refreshed at this cadence, not every step.
  TimeNs nextSlowRefresh_ = 0;
  double ch3V_ = 0.0;
  double tempSenseF_ = 0.0;
  // exp(-dt/tau) of the LM2907 lag for the last dt (dt is almost always the tick).
  double lagDt_ = -1.0, lagTau_ = -1.0, lagK_ = 0.0;
};

}  // namespace xr::sim

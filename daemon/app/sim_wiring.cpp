#include "app/sim_wiring.h"

#include <spdlog/spdlog.h>

#include <csignal>
#include <cstdlib>
#include <exception>
#include <stdexcept>

#include "app/can_wiring.h"
#include "config/config.h"

namespace xr::app {

namespace {
sim::SimRigOptions rigOptions(const CliOptions& cli, std::ostream* canLog,
                              std::optional<double> tachPulleyRatio) {
  sim::SimRigOptions o;
  o.canLog = canLog;
  o.tachPulleyRatio = tachPulleyRatio;
  o.batteryProbeAsConfigured = true;
  if (cli.seed) o.seed = *cli.seed;
  o.speed = 0.0;  // pacing is ours (PacedClock) so the period error is measured
  return o;
}
}  // namespace

bool scenarioConfigFits(const Params& effective, const std::string& source) {
  const auto errs = checkConsistency(effective, source);
  for (const auto& e : errs) {
    spdlog::critical("{}: [config] {}", source, e.toString());
    std::fprintf(stderr, "xregulatord: %s: [config] %s\n", source.c_str(), e.toString().c_str());
  }
  return errs.empty();
}

void applyScenarioWeather(const sim::Scenario& scenario, WeatherSettings& weather) {
  if (!scenario.weather) return;
  const sim::ScenarioWeather& w = *scenario.weather;
  weather.enabled = true;
  weather.url = w.url;
  if (w.latitude) weather.latitude = *w.latitude;
  if (w.longitude) weather.longitude = *w.longitude;
  if (w.refresh_min) weather.refresh_min = *w.refresh_min;
}

SimWiring::SimWiring(const sim::Scenario& scenario, const Settings& settings, const CliOptions& cli,
                     std::unique_ptr<std::ofstream> canLog, std::optional<double> tachPulleyRatio)
    : cli_(cli),
      canLog_(std::move(canLog)),
      rig_(scenario, settings, rigOptions(cli, canLog_.get(), tachPulleyRatio)),
      buttonWired_(settings.pairing.button_line >= 0) {
  rig_.onCanReport([](const std::string& what) { spdlog::warn("{}", what); });
  rig_.onScenarioProblem(
      [](int line, const std::string& what) { spdlog::error("scenario line {}: {}", line, what); });
  if (cli.speed > 0.0) paced_ = std::make_unique<rt::PacedClock>(rig_.clock(), wall_, cli.speed);
  if (cli.simOutputs) {
    sim::SimWorld& w = rig_.world();
    mirror_ = std::make_unique<rt::OutputMirror>(*cli.simOutputs);
    mPwm_ = std::make_unique<rt::MirroredPwm>(w.pwm(), *mirror_);
    mEnable_ = std::make_unique<rt::MirroredDigitalOutput>(w.fieldEnable(), *mirror_,
                                                           rt::MirroredDigitalOutput::Role::FieldEnable);
    mBuzzer_ = std::make_unique<rt::MirroredDigitalOutput>(w.buzzer(), *mirror_,
                                                           rt::MirroredDigitalOutput::Role::Buzzer);
  }
}

rt::CycleDevices SimWiring::devices() {
  rt::CycleDevices d = rig_.devices();
  if (mPwm_) d.pwm = mPwm_.get();
  if (mEnable_) d.fieldEnable = mEnable_.get();
  if (mBuzzer_) d.buzzer = mBuzzer_.get();
  d.hook = this;
  return d;
}

std::function<TimeNs(TimeNs)> SimWiring::wallDeadlineOf() {
  if (!paced_) return {};
  rt::PacedClock* p = paced_.get();
  return [p](TimeNs t) { return p->wallDeadline(t); };
}

void SimWiring::beforeTick(TimeNs now) {
  if (cli_.testFault == TestFault::None || faultFired_ || toSec(now - rig_.start()) < cli_.testFaultAtS)
    return;
  switch (cli_.testFault) {
    case TestFault::Segv:
      faultFired_ = true;
      std::raise(SIGSEGV);
      break;
    case TestFault::Abort:
      faultFired_ = true;
      std::abort();
    case TestFault::Terminate:
      faultFired_ = true;
      std::terminate();
    case TestFault::ThrowInControl:
      faultFired_ = true;
      throw std::runtime_error("test fault: exception in the control thread");
    default:
      break;  // Throw is raised on the main thread
  }
}

}  // namespace xr::app

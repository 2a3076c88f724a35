#pragma once
// The daemon side of the web server (web/server/daemon_api.h). Every method
// is a non-blocking hand-off for the control thread: status from the
// seqlock, commands into the SPSC queue, a validated whole Params into the
// triple buffer (then persisted as overrides), events from memory, history
// from the store.
#include <atomic>
#include <chrono>
#include <functional>
#include <mutex>
#include <optional>
#include <set>
#include <vector>

#include "app/can_status.h"
#include "app/patch_log_limiter.h"
#include "app/status_source.h"
#include "app/store_service.h"
#include "app/update_watch.h"
#include "config/param_sources.h"
#include "runtime/handoffs.h"
#include "web/server/daemon_api.h"

namespace xr::app {

struct WebApiContext {
  rt::Handoffs* handoffs = nullptr;
  Params fileParams;
  ParamOrigins origins;  // where each value comes from (docs/configuration.md)
  // The configured set before the "not set up" limits (runningParams()),
  // which a PATCH starts from; unset: the set in force.
  std::optional<Params> configured;
  StoreService* store = nullptr;  // may be null (no --state-db in --sim)
  RecentEvents* events = nullptr;
  bool sim = false;
  double controlPeriodUs = 2500;
  std::atomic<std::int64_t>* lastHeartbeatWallMs = nullptr;  // set by the supervisor
  std::atomic<bool>* fieldSafeFault = nullptr;               // outputs could not be driven
  // How long POST /api/commands waits for the regulator's answer.
  std::chrono::milliseconds commandAckTimeout{1000};
  // The integrations' state (docs/integrations.md); empty when none runs.
  std::function<std::vector<web::IntegrationState>()> integrations;
  // The set-up page's hardware choices (config/hardware_choices.h): the
  // file's settings, the ones this run opened its devices with, and where
  // its 1-Wire probes are (the simulator's own tree in --sim).
  Settings fileSettings;
  Settings runningSettings;
  std::string w1Root;
  std::string sysClassNet = "/sys/class/net";
  const UpdateWatch* update = nullptr;  // the package's version, channel and install time
};

class WebApi final : public web::DaemonApi {
 public:
  explicit WebApi(WebApiContext ctx) : ctx_(std::move(ctx)) {}
  bool latestStatus(web::StatusSnapshot& out) override;
  Params currentParams() override;
  Params fileParams() override { return ctx_.fileParams; }
  std::map<std::string, std::string> paramSources() override;
  std::set<std::string> profileOwned() override;
  Params effectiveDefaults() override;
  SetupState setupState() override;
  web::PatchResult patchParams(const std::vector<web::ParamChange>& changes, const std::string& source,
                               const web::PatchOptions& opts = {}) override;
  web::CommandResult command(const Command& cmd) override;
  web::CommandResult dvccLimits(const web::DvccRequest& req) override;  // web_api_dvcc.cpp
  void securityEvent(const std::string& text) override;
  std::vector<web::EventRecord> events(const web::EventQuery& q) override;
  web::HistoryResult history(const web::HistoryQuery& q) override;
  std::vector<DaySummary> historyDays(std::size_t n) override {
    return ctx_.store ? ctx_.store->days(n) : std::vector<DaySummary>{};
  }
  std::vector<ChargeSummary> historyCharges(std::size_t n) override {
    return ctx_.store ? ctx_.store->charges(n) : std::vector<ChargeSummary>{};
  }
  std::optional<std::vector<ChargeSummary>> historyChargesOn(const std::string& day) override {
    const auto bounds = StoreService::dayBoundsMs(day);
    if (!bounds) return std::nullopt;
    return ctx_.store ? ctx_.store->chargesBetween(bounds->first, bounds->second)
                      : std::vector<ChargeSummary>{};
  }
  std::vector<TrendRow> historyTrends(std::int64_t fromS, std::int64_t toS, bool daily) override {
    return ctx_.store ? ctx_.store->trends(fromS, toS, daily) : std::vector<TrendRow>{};
  }
  std::vector<web::ProbeResult> probeResults() override;
  web::VersionMap versions() override;
  web::Health health() override;
  std::vector<web::IntegrationState> integrations() override {
    return ctx_.integrations ? ctx_.integrations() : std::vector<web::IntegrationState>{};
  }

  web::CanState can() override {
    return canStateOf(ctx_.handoffs->canStatus.load(), ctx_.handoffs->acceptedParams().BmsLimitsEnabled);
  }

  web::HardwareSetup hardwareSetup() override;  // web_api_hardware.cpp
  std::vector<web::FieldError> saveHardwareChoices(const web::HardwareChoiceEdit& edit,
                                                   const std::string& source) override;

  static web::StatusSnapshot toStatus(const rt::RuntimeSnapshot& s, bool sim, double periodUs);
  // Once a second from the supervisor: the summary line of the settings
  // changes the journal's rate limit held back (patch_log_limiter.h).
  void flushPatchLog(PatchLogLimiter::Clock::time_point now = PatchLogLimiter::Clock::now());

 private:
  void logPatch(std::size_t values);
  // An event of the daemon's own (not the core's): into the store, and the
  // in-memory list that serves without one.
  void recordEvent(const std::string& code, const std::string& text);
  void recordPatchEvent(const Params& before, const Params& after, const std::vector<std::string>& named,
                        const std::string& source, bool setupDone);  // web_api_params.cpp

  WebApiContext ctx_;
  std::mutex patchMutex_;  // read-modify-write of the whole Params
  std::mutex logMutex_;
  PatchLogLimiter patchLog_;
  std::mutex dvccMutex_;  // Handoffs::dvcc has one writer at a time
  bool dvccFollowing_ = false;
  std::set<std::string> dvccRefusalsTold_;  // the journal hears each kind of refusal once
};

}  // namespace xr::app

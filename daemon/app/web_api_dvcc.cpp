// WebApi: a Victron GX's DVCC limits (POST /api/dvcc) into the control
// thread's BMS-limit path (core/dvcc_limits.h, docs/integrations.md
// "Victron GX"). The web server's threads call this concurrently: one mutex
// keeps Handoffs::dvcc single-writer. The journal hears when the limits
// start to be followed and each kind of refusal once, not once a second.
#include <spdlog/spdlog.h>

#include <cmath>

#include "app/web_api.h"
#include "core/dvcc_limits.h"

namespace xr::app {

namespace {
std::string show(double v, const char* unit) {
  return std::isnan(v) ? "none" : fmt::format("{:.2f} {}", v, unit);
}
}  // namespace

web::CommandResult WebApi::dvccLimits(const web::DvccRequest& req) {
  std::lock_guard lock(dvccMutex_);
  // The server has read the body; the values are checked here, where they
  // are applied.
  std::string why = req.refusal;
  if (why.empty()) why = dvccVoltageRefusal(req.chargeVoltageV);
  if (why.empty()) why = dvccCurrentRefusal(req.chargeCurrentA);
  if (why.empty() && std::isnan(req.chargeVoltageV) && std::isnan(req.chargeCurrentA))
    why = "neither charge_voltage_v nor charge_current_a";
  const TimeNs now = ctx_.handoffs->latest().telemetry.now;
  if (why.empty() && now <= 0) why = "the regulator has not ticked yet";
  if (!why.empty()) {
    // Each kind once until a good one (a bounded set: a writer cannot grow it).
    if (dvccRefusalsTold_.size() < 16 && dvccRefusalsTold_.insert(why).second)
      spdlog::warn("dvcc: refused limits from {}: {} (told once until the next good one)", req.source, why);
    return {false, why};
  }
  dvccRefusalsTold_.clear();
  BmsLimits d;
  d.cvlV = req.chargeVoltageV;
  d.cclA = req.chargeCurrentA;
  d.source = BmsSource::VictronGx;  // DVCC comes from the GX
  d.stamp = now;                    // the control clock: BmsStaleS runs on the regulator's time
  ctx_.handoffs->dvcc.store(d);
  if (!dvccFollowing_)
    spdlog::info("dvcc: following the GX's limits from {}: charge voltage {}, charge current {}", req.source,
                 show(d.cvlV, "V"), show(d.cclA, "A"));
  dvccFollowing_ = true;
  return {true,
          "DVCC limits taken: charge voltage " + show(d.cvlV, "V") + ", charge current " + show(d.cclA, "A")};
}

}  // namespace xr::app

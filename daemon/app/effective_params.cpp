#include "app/effective_params.h"

#include "config/config.h"

namespace xr::app {

Params withDashboardLayer(const Params& fileParams, const OverrideResolution& resolved, ParamOrigins& origins,
                          std::string* why) {
  origins.dashboard = NameSet(resolved.applied.begin(), resolved.applied.end());
  Params p = applyLayers(resolved.params, origins);
  const auto errs = checkConsistency(p);
  if (errs.empty()) return p;
  if (why)
    *why = "the stored dashboard settings do not fit the battery profile (" + errs.front().message +
           "); they are set aside and the configuration file's values apply";
  origins.dashboard.clear();
  return applyLayers(fileParams, origins);
}

Params withPatch(const Params& p, const std::vector<std::string>& patched, ParamOrigins& origins) {
  origins.dashboard.insert(patched.begin(), patched.end());
  return applyLayers(p, origins);
}

}  // namespace xr::app

// The dashboard's parameter layer (docs/configuration.md "One chain of
// values"): GET's sources, and PATCH — set a value, or drop the dashboard's
// value (JSON null) so the file, the battery profile or the default applies
// again. The web server only parses the body: every check is here, once —
// each value against the catalogue, then the whole set as the daemon's start
// checks it, against the bank the regulator measures — then saved and
// applied, or nothing at all. A dry run answers the checked set and stops.
#include <algorithm>
#include <cmath>

#include "app/effective_params.h"
#include "app/param_change_text.h"
#include "app/web_api.h"
#include "config/battery_profiles.h"
#include "config/config.h"
#include "config/format.h"
#include "config/param_values.h"
#include "config/setup_pending.h"
#include "params/derived.h"

namespace xr::app {
namespace {

std::size_t slots(const ParamSpec& spec) { return spec.kind == ParamKind::Table ? RPM_TABLE_SIZE : 1; }

void copyValue(const ParamSpec& spec, const Params& from, Params& to) {
  for (std::size_t i = 0; i < slots(spec); ++i) spec.set(to, i, spec.get(from, i));
}

// A PATCH on its way: the set with its values written in, and the names it
// sets (joining the dashboard layer) or drops (back to the layer below).
struct PatchDraft {
  Params p;
  ParamOrigins origins;
  std::vector<std::string> patched, dropped;
  bool names(std::string_view n) const {
    return std::find(patched.begin(), patched.end(), n) != patched.end();
  }
};

// The layer below: the file's value (its default when the file has none);
// the battery profile refills it when it owns the name.
void dropName(const ParamSpec& spec, const Params& fileParams, PatchDraft& d) {
  const std::string name(spec.name);
  d.origins.dashboard.erase(name);
  copyValue(spec, fileParams, d.p);
  if (std::find(d.dropped.begin(), d.dropped.end(), name) == d.dropped.end()) d.dropped.push_back(name);
}

// Writes the changes into the draft; each value is checked against the
// catalogue here, with the file loader's words (config/param_values.h), the
// only range check a PATCH meets. A table is checked whole.
void writeChanges(const std::vector<web::ParamChange>& changes, const Params& fileParams, PatchDraft& d,
                  std::vector<web::FieldError>& errors) {
  for (const auto& c : changes) {
    if (!c.spec) {
      errors.push_back({"", "unknown parameter"});
      continue;
    }
    const std::string name(c.spec->name);
    if (c.drop) {
      dropName(*c.spec, fileParams, d);
      continue;
    }
    const std::size_t idx = c.index < 0 ? 0 : static_cast<std::size_t>(c.index);
    if (idx >= slots(*c.spec)) {
      errors.push_back({name, "no element " + std::to_string(idx)});
      continue;
    }
    if (c.spec->kind != ParamKind::Table)
      if (std::string why = checkParamValue(*c.spec, c.value); !why.empty()) {
        errors.push_back({name, why});
        continue;
      }
    c.spec->set(d.p, idx, c.value);
    if (!d.names(name)) d.patched.push_back(name);
  }
  for (const auto& name : d.patched)
    if (const ParamSpec* spec = findParam(name); spec->kind == ParamKind::Table)
      if (std::string why = checkParamValue(*spec, getParamValue(d.p, *spec)); !why.empty())
        errors.push_back({name, why});
}

// The set-up's bank choice (PatchOptions::bankV) as values: a chemistry gets
// its cell count for that bank, and its own values again where the
// dashboard had set them (docs/batteries.md); a custom set has its bank
// voltages moved to that bank (params/derived.h withBankClass). Empty, or
// why the choice is refused.
std::string applyBankChoice(int bankV, const Params& fileParams, PatchDraft& d) {
  if (bankV == 0) return "";
  if (bankV != 12 && bankV != 24 && bankV != 48) return "expected a 12, 24 or 48 V bank";
  const auto id = static_cast<BatteryProfileId>(d.p.BatteryProfile);
  if (profileTable(id)) {
    if (!d.names("BatteryCells")) {
      d.p.BatteryCells = cellsForNominal(id, bankV);
      d.patched.emplace_back("BatteryCells");
    }
    for (std::string_view n : profileOwnedNames())
      if (d.origins.dashboard.contains(n) && !d.names(n)) dropName(*findParam(n), fileParams, d);
    return "";
  }
  const auto to = static_cast<SystemClass>(bankV);
  if (systemClass(d.p) == to) return "";
  const Params moved = withBankClass(d.p, to);
  for (const ParamSpec& spec : catalogue()) {
    if (spec.kind == ParamKind::Table || !isBankVoltage(spec, spec.get(d.p, 0))) continue;
    spec.set(d.p, 0, spec.get(moved, 0));
    if (!d.names(spec.name)) d.patched.emplace_back(spec.name);
  }
  return "";
}

// The whole set must be for the bank the regulator measures: a set-up that
// picks 24 V (BatteryCells = 8) on a bank reading 12.8 V is refused, as one
// BulkVoltage of 28.8 V is (the bank size check would cut the field anyway).
std::string bankError(const Params& p, double batteryV) {
  if (!std::isfinite(batteryV) || batteryV < 4.5) return "";
  const int measured = nominalVoltage(bankClassOfVoltage(batteryV));
  const int set = nominalVoltage(systemClass(p));
  if (measured == set) return "";
  return "these settings are for a " + std::to_string(set) + " V bank (BulkVoltage " +
         formatNumber(p.BulkVoltage) + " V); this battery measures as a " + std::to_string(measured) +
         " V bank";
}

// Not set up: a value the patch names may not sit above the lowered set (it
// would run lowered without a word, and leak once the limits are lifted); a
// stored one is lowered by the running layer (config/setup_pending.h).
void addSetupPendingErrors(const Params& p, const ParamOrigins& origins,
                           const std::vector<std::string>& patched, web::PatchResult& r) {
  if (origins.setUp()) return;
  for (const auto& e : checkSetupPendingTargets(p))
    if (std::find(patched.begin(), patched.end(), e.key) != patched.end())
      r.errors.push_back({e.key, e.message});
}

// The checks of the whole set, the same the daemon's start runs
// (config/config.h checkConsistency), and the bank the battery measures
// (batteryV NaN: none measured yet).
void checkWholeSet(const Params& p, const PatchDraft& d, double batteryV, web::PatchResult& r) {
  // Bare parameter names, like every other error of the API: the loader's
  // keys carry the file's table ("voltage.").
  for (const auto& e : checkConsistency(p))
    r.errors.push_back({e.key.substr(e.key.rfind('.') + 1), e.message});
  addSetupPendingErrors(p, d.origins, d.patched, r);
  if (std::string e = bankError(p, batteryV); !e.empty()) r.errors.push_back({"BulkVoltage", e});
}

}  // namespace

Params WebApi::currentParams() { return ctx_.handoffs->acceptedParams(); }

std::map<std::string, std::string> WebApi::paramSources() {
  std::lock_guard lock(patchMutex_);
  std::map<std::string, std::string> out;
  for (const auto& s : catalogue()) out.emplace(s.name, toString(ctx_.origins.of(s.name)));
  return out;
}

// The profile's values for the bank the owner has (its cells and capacity),
// nothing pinned but the cell count: what "Default" puts back.
Params WebApi::effectiveDefaults() {
  const Params cur = currentParams();
  Params base{};
  base.BatteryProfile = cur.BatteryProfile;
  // Cells 0 = from the voltage class of the bulk voltage in force.
  base.BatteryCells = cur.BatteryCells > 0
                          ? cur.BatteryCells
                          : cellsForNominal(static_cast<BatteryProfileId>(cur.BatteryProfile),
                                            nominalVoltage(systemClass(cur)));
  base.BatteryCapacity_Ah = cur.BatteryCapacity_Ah;
  return applyBatteryProfile(base, NameSet{"BatteryCells"}).params;
}

web::DaemonApi::SetupState WebApi::setupState() {
  std::lock_guard lock(patchMutex_);
  if (ctx_.origins.setUp()) return {};
  return {false, setupPendingLimitsText(ctx_.handoffs->acceptedParams())};
}

std::set<std::string> WebApi::profileOwned() {
  std::set<std::string> out;
  for (std::string_view n : profileOwnedNames()) out.emplace(n);
  return out;
}

web::PatchResult WebApi::patchParams(const std::vector<web::ParamChange>& changes, const std::string& source,
                                     const web::PatchOptions& opts) {
  web::PatchResult r;
  std::lock_guard lock(patchMutex_);
  const Params before = ctx_.configured.value_or(ctx_.handoffs->acceptedParams());
  PatchDraft d{before, ctx_.origins, {}, {}};
  writeChanges(changes, ctx_.fileParams, d, r.errors);
  if (std::string e = applyBankChoice(opts.bankV, ctx_.fileParams, d); !e.empty())
    r.errors.push_back({"bank", e});
  if (!r.errors.empty()) return r;  // nothing applied
  // The patched names join the dashboard layer; the battery profile fills
  // again what nobody set (a new BatteryProfile, BatteryCells or capacity
  // moves its values), and the whole set is checked (docs/batteries.md).
  const Params p = withPatch(d.p, d.patched, d.origins);
  web::StatusSnapshot snap;
  checkWholeSet(p, d, latestStatus(snap) ? snap.telemetry.battery_v : std::nan(""), r);
  // What would run: a dry run's answer (the set-up page shows these).
  ParamOrigins running = d.origins;
  r.values = runningParams(p, running);
  if (opts.dryRun || !r.errors.empty()) return r;  // nothing applied, nothing stored
  // Saved first, applied second: a change that cannot be saved is refused,
  // not applied for this run only and silently lost at the next start.
  if (ctx_.store) {
    // Only what the patch named is stored: values the profile moved stay the
    // profile's, and follow it at the next start.
    Params named = before;
    for (const auto& name : d.patched) copyValue(*findParam(name), p, named);
    const std::string why = ctx_.store->saveOverrides(ctx_.fileParams, before, named, d.dropped);
    if (!why.empty()) {
      r.errors.push_back({"store", why + "; nothing applied"});
      return r;
    }
  }
  const bool wasSetUp = ctx_.origins.setUp();
  if (ctx_.configured) ctx_.configured = p;
  ctx_.handoffs->submitParams(runningParams(p, d.origins));  // whole swap, between ticks
  ctx_.origins = std::move(d.origins);
  ctx_.handoffs->setUp.store(ctx_.origins.setUp());
  logPatch(changes.size());
  std::vector<std::string> named = d.patched;
  named.insert(named.end(), d.dropped.begin(), d.dropped.end());
  recordPatchEvent(before, p, named, source, !wasSetUp && ctx_.origins.setUp());
  return r;
}

// Who changed what, in the event list; a PATCH that changes nothing (the
// same values again) makes no event. The set-up page's save is one line,
// whoever asked; the first one lifts the "not set up" limits and says so in
// the same line.
void WebApi::recordPatchEvent(const Params& before, const Params& after,
                              const std::vector<std::string>& named, const std::string& source,
                              bool setupDone) {
  const std::string changedText = paramChangeText(before, after, named, source);
  if (isSetupSave(named)) {
    if (changedText.empty() && !setupDone) return;
    recordEvent(setupDone ? "SetupDone" : "ParamsChanged",
                setupSummaryText(after) + ", by " + (source.empty() ? std::string("the web API") : source) +
                    (setupDone ? " (the \"not set up\" limits are lifted)" : ""));
    return;
  }
  if (setupDone)
    recordEvent("SetupDone", "Battery type chosen (" +
                                 std::string(choiceName(*findParam("BatteryProfile"), after.BatteryProfile)) +
                                 "): the \"not set up\" limits are lifted");
  if (!changedText.empty()) recordEvent("ParamsChanged", changedText);
}

}  // namespace xr::app

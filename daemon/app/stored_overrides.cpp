#include "app/stored_overrides.h"

#include <sqlite3.h>

#include <algorithm>
#include <cstddef>

#include "config/config.h"
#include "config/param_sources.h"
#include "store/param_overrides.h"
#include "store/sqlite_db.h"

namespace xr::app {

std::string DroppedOverride::text() const {
  return "stored dashboard setting " + name + " = " + value + " dropped: " + why +
         "; the configuration file's value applies";
}

namespace {

struct Candidate {
  const ParamSpec* spec;
  const OverrideRow* row;
  bool active = true;
};

Params applyActive(const Params& fileParams, const std::vector<Candidate>& cands, std::size_t skip) {
  Params p = fileParams;
  for (std::size_t i = 0; i < cands.size(); ++i)
    if (cands[i].active && i != skip) parseParamValue(*cands[i].spec, cands[i].row->value, p, nullptr);
  return p;
}

// The set as the daemon will run it: the battery profile re-applied with the
// file's names and the active overrides pinned (effective_params.h). A stored
// BatteryProfile moves every value it owns, so the raw values alone would be
// judged against the old profile's (LiFePO4 against AGM's -45 degC limit).
std::vector<ConfigError> errorsOf(const Params& fileParams, const NameSet& fileNames,
                                  const std::vector<Candidate>& cands, std::size_t skip) {
  ParamOrigins o;
  o.file = fileNames;
  for (std::size_t i = 0; i < cands.size(); ++i)
    if (cands[i].active && i != skip) o.dashboard.emplace(cands[i].spec->name);
  return checkConsistency(applyLayers(applyActive(fileParams, cands, skip), o));
}

// Consistency errors are keyed "group.Name" or "Name": compare the bare name.
bool names(const std::vector<ConfigError>& errs, std::string_view name) {
  for (const auto& e : errs) {
    const auto dot = e.key.rfind('.');
    if ((dot == std::string::npos ? std::string_view(e.key) : std::string_view(e.key).substr(dot + 1)) ==
        name)
      return true;
  }
  return false;
}

std::string describe(const std::vector<ConfigError>& errs) {
  std::string s;
  for (const auto& e : errs) {
    if (!s.empty()) s += "; ";
    s += e.message;
  }
  return s;
}

}  // namespace

OverrideResolution resolveStoredOverrides(const Params& fileParams, const NameSet& fileNames,
                                          const std::vector<OverrideRow>& rows) {
  OverrideResolution r;
  std::vector<Candidate> cands;
  for (const auto& row : rows) {
    const ParamSpec* spec = findParam(row.name);
    if (!spec) {
      r.dropped.push_back({row.name, row.value, "no parameter of that name any more"});
      continue;
    }
    Params probe = fileParams;
    std::string err;
    if (!parseParamValue(*spec, row.value, probe, &err)) {
      r.dropped.push_back({row.name, row.value, err});
      continue;
    }
    cands.push_back({spec, &row});
  }
  const std::size_t none = cands.size();
  auto errs = errorsOf(fileParams, fileNames, cands, none);
  while (!errs.empty()) {
    std::size_t best = none;
    std::size_t bestCount = 0;
    bool bestNamed = false;
    for (std::size_t i = 0; i < cands.size(); ++i) {
      if (!cands[i].active) continue;
      const std::size_t count = errorsOf(fileParams, fileNames, cands, i).size();
      const bool named = names(errs, cands[i].spec->name);
      const bool better = best == none || count < bestCount || (count == bestCount && named && !bestNamed) ||
                          (count == bestCount && named == bestNamed &&
                           cands[i].row->changedAtMs > cands[best].row->changedAtMs);
      if (better) {
        best = i;
        bestCount = count;
        bestNamed = named;
      }
    }
    if (best == none) break;  // only the file is left; the loader refuses an inconsistent file
    cands[best].active = false;
    r.dropped.push_back({cands[best].row->name, cands[best].row->value,
                         "it does not fit the other values: " + describe(errs)});
    errs = errorsOf(fileParams, fileNames, cands, none);
  }
  r.params = applyActive(fileParams, cands, none);
  for (const auto& c : cands)
    if (c.active) r.applied.push_back(c.row->name);
  return r;
}

namespace {

bool openReadOnly(sql::Db& db, const std::string& path, std::string* error) {
  const int rc = db.open(path, SQLITE_OPEN_READONLY);
  if (rc != SQLITE_OK) {
    if (error) *error = "cannot open " + path + " read-only: " + db.lastError();
    return false;
  }
  return true;
}

}  // namespace

std::vector<OverrideRow> readOverridesReadOnly(const std::string& dbPath, std::string* error) {
  std::vector<OverrideRow> out;
  sql::Db db;
  if (!openReadOnly(db, dbPath, error)) return out;
  sql::Stmt st(db, "SELECT name, value, file_value, changed_at_ms FROM overrides ORDER BY name");
  if (!st.ok()) {
    if (error) *error = dbPath + ": no readable overrides table: " + db.lastError();
    return out;
  }
  int rc;
  while ((rc = st.step()) == SQLITE_ROW)
    out.push_back(OverrideRow{st.colText(0), st.colText(1), st.colText(2), st.colInt(3)});
  if (rc != SQLITE_DONE && error) *error = dbPath + ": " + db.lastError();
  return out;
}

std::string readTokenReadOnly(const std::string& dbPath, std::string* error) {
  sql::Db db;
  if (!openReadOnly(db, dbPath, error)) return {};
  sql::Stmt st(db, "SELECT value FROM kv WHERE key = 'web_token'");
  if (!st.ok()) {
    if (error) *error = dbPath + ": no token stored: " + db.lastError();
    return {};
  }
  return st.step() == SQLITE_ROW ? st.colText(0) : std::string();
}

HardwareChoices hardwareChoicesReadOnly(const std::string& dbPath) {
  sql::Db db;
  HardwareChoices c;
  if (!openReadOnly(db, dbPath, nullptr)) return c;
  auto read = [&](const char* key) -> std::optional<std::string> {
    sql::Stmt st(db, "SELECT value FROM kv WHERE key = ?1");
    if (!st.ok() || st.bind(1, std::string_view(key)).step() != SQLITE_ROW) return std::nullopt;
    return st.colText(0);
  };
  c.batteryTempSensor = read(kChoiceBatteryTempSensor);
  c.bmsInterface = read(kChoiceBmsInterface);
  c.pulleyRatio = parseChoiceNumber(read(kChoicePulleyRatio));
  return c;
}

bool setUpBeforeUpgradeReadOnly(const std::string& dbPath) {
  sql::Db db;
  if (!openReadOnly(db, dbPath, nullptr)) return false;
  if (db.queryInt("PRAGMA user_version") >= 4) {
    sql::Stmt st(db, "SELECT 1 FROM kv WHERE key = 'set_up_before_upgrade'");
    return st.ok() && st.step() == SQLITE_ROW;
  }
  sql::Stmt st(db, "SELECT (EXISTS (SELECT 1 FROM ledger_meta)) OR (EXISTS (SELECT 1 FROM overrides))");
  return st.ok() && st.step() == SQLITE_ROW && st.colInt(0) != 0;
}

}  // namespace xr::app

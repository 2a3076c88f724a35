#pragma once
// The values the daemon runs with, checked as ONE set (docs/security.md):
// the file (with a scenario's [config]) plus the dashboard's stored
// overrides go through the same cross-parameter checks as the file alone.
//
// An override that no longer fits — the file changed under it (Absorption
// lowered below a stored Float), the catalogue narrowed its range, the name
// is gone — is dropped: the daemon runs on the file's value, names the
// dropped value in an event, and forgets the row. Never a silent unsafe set,
// never a refusal to start.
#include <string>
#include <vector>

#include "config/battery_profiles.h"
#include "config/hardware_choices.h"
#include "params/params.h"
#include "store/store.h"

namespace xr::app {

struct DroppedOverride {
  std::string name;          // the parameter ("FloatVoltage")
  std::string value;         // the stored value that was dropped
  std::string why;           // the check it failed
  std::string text() const;  // "stored dashboard setting FloatVoltage = 14.3 dropped: ..."
};

struct OverrideResolution {
  Params params;  // file + every override that fits (profile re-applied by withDashboardLayer)
  std::vector<DroppedOverride> dropped;  // in the order they were dropped
  std::vector<std::string> applied;      // names of the overrides in force (their source)
};

// Deterministic: first every row that is malformed on its own (unknown name,
// not a number, out of the catalogue range) is dropped; then, while the set
// is inconsistent, the one override whose removal leaves the fewest
// cross-parameter errors (ties: one the errors name, then the most recently
// changed) is dropped. fileParams must be consistent (the loader checked it);
// fileNames are the names the file (and a scenario's [config]) wrote. The set
// is judged as it will run: with the battery profile re-applied over it.
OverrideResolution resolveStoredOverrides(const Params& fileParams, const NameSet& fileNames,
                                          const std::vector<OverrideRow>& rows);

// Read-only look at a state database for --check-config: the override rows,
// or empty with *error set when the file cannot be opened or read. Never
// creates, migrates or moves the file.
std::vector<OverrideRow> readOverridesReadOnly(const std::string& dbPath, std::string* error);
// The stored web token (empty when none), read-only, for --print-token.
std::string readTokenReadOnly(const std::string& dbPath, std::string* error);
// True when the database belongs to an install that ran before "not set up"
// existed (store/schema.cpp, v4): the flag, or for a database not migrated
// yet, a saved ledger or a dashboard setting, which the migration will mark.
bool setUpBeforeUpgradeReadOnly(const std::string& dbPath);

// The set-up page's hardware choices kept in the database (none when it
// cannot be read), for --print-config.
HardwareChoices hardwareChoicesReadOnly(const std::string& dbPath);

}  // namespace xr::app

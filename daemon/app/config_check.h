#pragma once
// `xregulatord --check-config` and `--print-token` (docs/security.md):
// the file's own checks, then the stored dashboard overrides on top of it as
// one set, exactly as the daemon will resolve them at start, read-only.
#include <iosfwd>
#include <optional>
#include <string>

namespace xr::app {

// 0 when the daemon would start (dropped overrides and a world-readable
// token are warnings on out), kExitConfig (78) when the file is refused.
// stateDb: --state-db, else [store] path; a missing database is no error.
int checkConfigAndState(const std::string& configPath, const std::optional<std::string>& stateDb,
                        std::ostream& out, std::ostream& err);

// `--print-config` (docs/configuration.md): the effective configuration as TOML, each
// value with its source (# default / # profile / # file / # dashboard); the
// dashboard layer is read from the state database when there is one. 0, or
// kExitConfig (78) with the errors on err when the file is refused.
int printConfigMain(const std::optional<std::string>& configPath, const std::optional<std::string>& stateDb,
                    std::ostream& out, std::ostream& err);

// Prints the stored token on out. 0, or 1 with the reason on err.
int printTokenMain(const std::optional<std::string>& configPath, const std::optional<std::string>& stateDb,
                   std::ostream& out, std::ostream& err);

}  // namespace xr::app

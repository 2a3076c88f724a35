#pragma once
// Logging sink (docs/configuration.md): journald under systemd (JOURNAL_STREAM
// set) with real priorities, readable console lines otherwise. Events get one
// structured journal entry each with XREG_EVENT=, XREG_REASON=, XREG_MODE=,
// so `journalctl -u xregulatord XREG_REASON=REASON_INA_OVERVOLTAGE` works.
// Never call from the RT thread (formats and allocates).
#include <optional>
#include <string>
#include <string_view>

#include "config/settings.h"
#include "core/events.h"

namespace xr {

enum class LogTarget { Auto, Console, Journal };

// Parses "trace|debug|info|warn|warning|error|critical|off"; nullopt otherwise.
// Returns spdlog's level_enum as int to keep spdlog out of this header.
std::optional<int> parseLogLevel(std::string_view level);

// Installs the default spdlog logger. cliLevel (from --log-level) wins over
// settings.level. Returns an error text on a bad level (then logging is left
// at info), empty on success. Auto = journal when JOURNAL_STREAM is set.
std::string initLogging(const LogSettings& settings, std::optional<std::string_view> cliLevel = {},
                        LogTarget target = LogTarget::Auto);

// True when the logger writes to the journal.
bool loggingToJournal();

// One event, one line: describe(e) with the specification's console wording, at the
// priority of e.level, with the structured fields above on the journal.
void logEvent(const Event& e);

}  // namespace xr

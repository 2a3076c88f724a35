#include "logging/logging.h"

#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <mutex>

#include <spdlog/sinks/base_sink.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "logging/journal.h"

namespace xr {
namespace {

std::atomic<bool> gJournal{false};

// Each spdlog record becomes one journal entry with its real priority, so
// `journalctl -p warning` works; stderr prefixes (<4>) are not needed.
class JournalSink final : public spdlog::sinks::base_sink<std::mutex> {
 protected:
  void sink_it_(const spdlog::details::log_msg& msg) override {
    logging::JournalRecord r;
    r.fields.push_back("MESSAGE=" + std::string(msg.payload.data(), msg.payload.size()));
    r.fields.push_back("PRIORITY=" + std::to_string(logging::journalPriorityForSpdlog(static_cast<int>(msg.level))));
    r.fields.push_back("SYSLOG_IDENTIFIER=xregulatord");
    logging::sendToJournal(r);
  }
  void flush_() override {}
};

spdlog::level::level_enum toSpdlog(EventLevel l) {
  switch (l) {
    case EventLevel::Debug: return spdlog::level::debug;
    case EventLevel::Info: return spdlog::level::info;
    case EventLevel::Warning: return spdlog::level::warn;
    case EventLevel::Error: return spdlog::level::err;
    case EventLevel::Critical: return spdlog::level::critical;
  }
  return spdlog::level::info;
}

}  // namespace

std::optional<int> parseLogLevel(std::string_view s) {
  if (s == "trace") return spdlog::level::trace;
  if (s == "debug") return spdlog::level::debug;
  if (s == "info") return spdlog::level::info;
  if (s == "warn" || s == "warning") return spdlog::level::warn;
  if (s == "error" || s == "err") return spdlog::level::err;
  if (s == "critical") return spdlog::level::critical;
  if (s == "off") return spdlog::level::off;
  return std::nullopt;
}

std::string initLogging(const LogSettings& settings, std::optional<std::string_view> cliLevel, LogTarget target) {
  bool journal = false;
  if (target == LogTarget::Journal) journal = true;
  if (target == LogTarget::Auto) journal = logging::journalStreamMatches(std::getenv("JOURNAL_STREAM"), STDERR_FILENO);

  spdlog::sink_ptr sink;
  if (journal) {
    sink = std::make_shared<JournalSink>();
  } else {
    auto console = std::make_shared<spdlog::sinks::stderr_color_sink_mt>();
    console->set_pattern("%Y-%m-%d %H:%M:%S.%e %^%-5l%$ %v");
    sink = console;
  }
  auto logger = std::make_shared<spdlog::logger>("xregulatord", sink);
  logger->flush_on(spdlog::level::warn);
  spdlog::set_default_logger(logger);
  gJournal = journal;

  std::string error;
  const std::string_view wanted = cliLevel ? *cliLevel : std::string_view(settings.level);
  auto lvl = parseLogLevel(wanted);
  if (!lvl) {
    error = "unknown log level \"" + std::string(wanted) + "\" (use trace, debug, info, warn, error, critical or off)";
    lvl = spdlog::level::info;
  }
  logger->set_level(static_cast<spdlog::level::level_enum>(*lvl));
  return error;
}

bool loggingToJournal() { return gJournal; }

void logEvent(const Event& e) {
  auto logger = spdlog::default_logger();
  const auto lvl = toSpdlog(e.level);
  if (!logger->should_log(lvl)) return;
  if (gJournal) {
    logging::sendToJournal(logging::eventRecord(e));
    return;
  }
  // Console: the specification's wording first (grep-able), the structured fields after.
  if (e.reason != Reason::NONE)
    logger->log(lvl, "{} [event={} reason={} mode={}]", describe(e), toString(e.code), toString(e.reason),
                toString(e.mode));
  else
    logger->log(lvl, "{} [event={} mode={}]", describe(e), toString(e.code), toString(e.mode));
}

}  // namespace xr

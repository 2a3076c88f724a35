#pragma once
// journald details of the logging sink, apart so tests can check the exact
// fields without a running journal (a sender hook replaces sd_journal_sendv).
#include <functional>
#include <string>
#include <vector>

#include "core/events.h"

namespace xr::logging {

// One journal entry: "FIELD=value" strings (MESSAGE=, PRIORITY=, XREG_...=).
struct JournalRecord {
  std::vector<std::string> fields;
  // The value of field name, or empty.
  std::string field(std::string_view name) const;
};

// syslog priorities (sd-journal PRIORITY=): 2 crit, 3 err, 4 warning, 6 info, 7 debug.
int journalPriority(EventLevel level);
// spdlog level number (trace=0 ... critical=5) -> syslog priority.
int journalPriorityForSpdlog(int spdlogLevel);

// The structured entry for an event: MESSAGE=describe(e) with the specification's
// wording, PRIORITY=, SYSLOG_IDENTIFIER=xregulatord, XREG_EVENT=,
// XREG_REASON= (when a reason is acting), XREG_MODE=, XREG_T_S=.
JournalRecord eventRecord(const Event& e);

// True when JOURNAL_STREAM ("dev:ino") names the file open on fd, i.e. our
// stderr really goes to the journal (systemd.exec(5) "$JOURNAL_STREAM").
bool journalStreamMatches(const char* journalStreamEnv, int fd);

// Sends one record; returns 0 or a negative errno. Default: sd_journal_sendv.
using JournalSender = std::function<int(const JournalRecord&)>;
void setJournalSender(JournalSender sender);  // empty = restore the default
int sendToJournal(const JournalRecord& r);

}  // namespace xr::logging

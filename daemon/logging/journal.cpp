#include "logging/journal.h"

#include <sys/stat.h>
#include <sys/uio.h>
#include <systemd/sd-journal.h>

#include <cinttypes>
#include <cstdio>
#include <mutex>

namespace xr::logging {
namespace {

std::mutex gSenderMutex;
JournalSender& sender() {
  static JournalSender s;
  return s;
}

int defaultSend(const JournalRecord& r) {
  std::vector<iovec> iov;
  iov.reserve(r.fields.size());
  for (const auto& f : r.fields) iov.push_back({const_cast<char*>(f.data()), f.size()});
  return sd_journal_sendv(iov.data(), static_cast<int>(iov.size()));
}

}  // namespace

std::string JournalRecord::field(std::string_view name) const {
  for (const auto& f : fields)
    if (f.size() > name.size() && f.compare(0, name.size(), name) == 0 && f[name.size()] == '=')
      return f.substr(name.size() + 1);
  return {};
}

int journalPriority(EventLevel level) {
  switch (level) {
    case EventLevel::Debug: return 7;
    case EventLevel::Info: return 6;
    case EventLevel::Warning: return 4;
    case EventLevel::Error: return 3;
    case EventLevel::Critical: return 2;
  }
  return 6;
}

int journalPriorityForSpdlog(int lvl) {
  switch (lvl) {
    case 0:  // trace
    case 1: return 7;  // debug
    case 2: return 6;  // info
    case 3: return 4;  // warn
    case 4: return 3;  // err
    case 5: return 2;  // critical
  }
  return 6;
}

JournalRecord eventRecord(const Event& e) {
  JournalRecord r;
  r.fields.push_back("MESSAGE=" + describe(e));
  r.fields.push_back("PRIORITY=" + std::to_string(journalPriority(e.level)));
  r.fields.push_back("SYSLOG_IDENTIFIER=xregulatord");
  r.fields.push_back("XREG_EVENT=" + std::string(toString(e.code)));
  if (e.reason != Reason::NONE) r.fields.push_back("XREG_REASON=" + std::string(toString(e.reason)));
  r.fields.push_back("XREG_MODE=" + std::string(toString(e.mode)));
  char t[48];
  std::snprintf(t, sizeof t, "XREG_T_S=%.3f", static_cast<double>(e.t) / 1e9);
  r.fields.push_back(t);
  return r;
}

bool journalStreamMatches(const char* env, int fd) {
  if (!env || !*env) return false;
  std::uintmax_t dev = 0, ino = 0;
  if (std::sscanf(env, "%ju:%ju", &dev, &ino) != 2) return false;
  struct stat st {};
  if (fstat(fd, &st) != 0) return false;
  return static_cast<std::uintmax_t>(st.st_dev) == dev && static_cast<std::uintmax_t>(st.st_ino) == ino;
}

void setJournalSender(JournalSender s) {
  std::lock_guard lock(gSenderMutex);
  sender() = std::move(s);
}

int sendToJournal(const JournalRecord& r) {
  JournalSender s;
  {
    std::lock_guard lock(gSenderMutex);
    s = sender();
  }
  return s ? s(r) : defaultSend(r);
}

}  // namespace xr::logging

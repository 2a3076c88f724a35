#include "integrations/push_message.h"

#include <fmt/format.h>

#include <boost/json.hpp>
#include <cmath>

#include "core/wall_time_text.h"
#include "integrations/reason_words.h"

namespace xr::integrations {

namespace json = boost::json;

namespace {
std::string iso(double unixS) {
  return wallTimeText(static_cast<std::int64_t>(std::llround(unixS * 1000.0)), "%Y-%m-%dT%H:%M:%SZ",
                      TimeZone::Utc);
}
std::string lasted(double s) {
  if (s < 60.0) return fmt::format("{:.0f} s", s);
  if (s < 3600.0) return fmt::format("{:.0f} min", s / 60.0);
  return fmt::format("{:.1f} h", s / 3600.0);
}
// A header carries ASCII only: "°" and typographic quotes become plain ones.
std::string asciiOnly(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
      continue;
    }
    if (c == 0xe2 && i + 2 < s.size() && static_cast<unsigned char>(s[i + 1]) == 0x80) {
      const unsigned char d = static_cast<unsigned char>(s[i + 2]);
      out += (d == 0x9c || d == 0x9d) ? '"' : (d == 0x98 || d == 0x99) ? '\'' : '-';
      i += 2;
      continue;
    }
    if (c == 0xc2 && i + 1 < s.size() && static_cast<unsigned char>(s[i + 1]) == 0xb0) {
      out += " deg";
      ++i;
      continue;
    }
    if (c >= 0x80) {
      while (i + 1 < s.size() && (static_cast<unsigned char>(s[i + 1]) & 0xc0) == 0x80) ++i;
      out += '?';
    }
  }
  return out;
}
}  // namespace

IncidentWords incidentWords(const IncidentEdge& e) {
  const Incident& i = e.incident;
  const std::string code(toString(i.reason));
  const ReasonWords* w = reasonWords(code);
  IncidentWords out;
  out.title = w ? std::string(w->title) : code;
  out.whatHappened = w ? std::string(w->meaning) : "";
  out.whatToDo = w ? std::string(w->action) : "";
  out.severity = std::string(toString(i.level));
  for (auto& ch : out.severity) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  out.startIso = iso(i.startS);
  if (!e.start) {
    out.endIso = iso(i.endS);
    const std::string did = whatTheRegulatorDid(i);
    if (!did.empty()) out.whatHappened += (out.whatHappened.empty() ? "" : " ") + did;
    out.whatHappened +=
        (out.whatHappened.empty() ? "" : " ") + ("Over after " + lasted(i.endS - i.startS) + ".");
  }
  return out;
}

PushMessage pushMessage(const IncidentEdge& e, const std::string& regulator, const std::string& format) {
  const IncidentWords w = incidentWords(e);
  PushMessage m;
  m.incidentId = e.incident.id;
  m.start = e.start;
  // The same key on every retry of one edge: a receiver may drop the copy
  // of a delivery whose answer we never saw (docs/integrations.md).
  m.headers.emplace_back("Idempotency-Key", fmt::format("{}-{}-{}", asciiOnly(regulator), e.incident.id,
                                                        e.start ? "start" : "end"));
  if (format == "text") {
    m.contentType = "text/plain; charset=utf-8";
    m.headers.emplace_back("Title", asciiOnly(regulator + ": " + (e.start ? w.title : "over: " + w.title)));
    m.headers.emplace_back("Priority", e.start ? "high" : "default");
    m.headers.emplace_back("Tags", e.start ? "warning" : "white_check_mark");
    m.body = e.start
                 ? fmt::format("{} ({})\n{}\nWhat to do: {}", w.title, regulator, w.whatHappened, w.whatToDo)
                 : fmt::format("Over: {} ({})\n{}", w.title, regulator, w.whatHappened);
    return m;
  }
  m.contentType = "application/json";
  json::object o;
  o["event"] = e.start ? "start" : "end";
  o["incident_id"] = e.incident.id;
  o["title"] = w.title;
  o["what_happened"] = w.whatHappened;
  o["what_to_do"] = w.whatToDo;
  o["regulator"] = regulator;
  o["severity"] = w.severity;
  o["reason"] = std::string(toString(e.incident.reason));
  o["start"] = w.startIso;
  o["end"] = e.start ? json::value(nullptr) : json::value(w.endIso);
  o["duration_s"] =
      e.start ? json::value(nullptr) : json::value(std::round(e.incident.endS - e.incident.startS));
  m.body = json::serialize(o);
  return m;
}

}  // namespace xr::integrations

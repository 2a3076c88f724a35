// Incidents for the owner away (docs/integrations.md "Alarms that reach the
// owner"): the tracker groups a protection's events as the Events page does,
// the push says them in the dashboard's words, and [notify] refuses what the
// sender could not use.
#include <gtest/gtest.h>

#include <boost/json.hpp>

#include "config/config.h"
#include "config/notify_target.h"
#include "integrations/ha_discovery.h"
#include "integrations/incident_tracker.h"
#include "integrations/push_message.h"
#include "integrations/reason_words.h"

namespace xr::integrations {
namespace {

namespace json = boost::json;
constexpr double kT0 = 1'765'000'000.0;  // a wall-clock second

Event ev(EventCode c, Reason r = Reason::NONE, EventLevel l = EventLevel::Info) {
  return makeEvent(0, l, c, r);
}

// The events of one thermal fault, as the daemon emits them (trip, cut,
// alarm, clears, field on, alarm off), from kT0 + at.
struct Fed {
  std::vector<IncidentEdge> edges;
  IncidentTracker t;
  void feed(const Event& e, double at) {
    for (auto& x : t.onEvent(e, kT0 + at)) edges.push_back(x);
  }
  void poll(double at) {
    if (auto x = t.poll(kT0 + at)) edges.push_back(*x);
  }
  void thermalFault(double at, double lasting) {
    feed(ev(EventCode::ProtectionTrip, Reason::REASON_TEMP_WARNING, EventLevel::Error), at);
    feed(ev(EventCode::ProtectionTrip, Reason::REASON_TEMP_CRITICAL, EventLevel::Critical), at);
    feed(ev(EventCode::ImmediateCut, Reason::REASON_TEMP_CRITICAL, EventLevel::Critical), at);
    feed(ev(EventCode::FieldOff), at);
    feed(ev(EventCode::AlarmOn, Reason::NONE, EventLevel::Warning), at + 0.3);
    feed(ev(EventCode::ProtectionClear, Reason::REASON_TEMP_WARNING), at + lasting);
    feed(ev(EventCode::ProtectionClear, Reason::REASON_TEMP_CRITICAL), at + lasting);
    feed(ev(EventCode::FieldOn), at + lasting + 0.1);
    feed(ev(EventCode::AlarmOff), at + lasting + 1.0);
  }
};

TEST(IncidentTracker, ThermalFaultIsOneStartAndOneEndAfterTheSettle) {
  Fed f;
  f.thermalFault(8.0, 12.0);
  ASSERT_EQ(f.edges.size(), 1u);
  EXPECT_TRUE(f.edges[0].start);
  EXPECT_EQ(f.edges[0].incident.reason, Reason::REASON_TEMP_WARNING);  // the first trip opens it
  f.poll(20.0 + kIncidentSettleS - 0.1);
  EXPECT_EQ(f.edges.size(), 1u) << "not over until it stayed clear for the settle time";
  f.poll(20.0 + kIncidentSettleS);
  ASSERT_EQ(f.edges.size(), 2u);
  const Incident& end = f.edges[1].incident;
  EXPECT_FALSE(f.edges[1].start);
  EXPECT_EQ(end.id, f.edges[0].incident.id);
  EXPECT_EQ(end.reason, Reason::REASON_TEMP_CRITICAL) << "the worst reason names it";
  EXPECT_EQ(end.level, EventLevel::Critical);
  EXPECT_DOUBLE_EQ(end.endS - end.startS, 12.0);
  EXPECT_EQ(whatTheRegulatorDid(end),
            "The regulator cut the field at once, sounded the alarm, resumed charging.");
  f.poll(100.0);
  EXPECT_EQ(f.edges.size(), 2u) << "one end only";
}

TEST(IncidentTracker, ATripWithinTheSettleIsTheSameIncident) {
  Fed f;
  f.thermalFault(0.0, 3.0);
  f.thermalFault(3.0 + kIncidentSettleS - 1.0, 3.0);  // flickering at its threshold
  f.poll(100.0);
  ASSERT_EQ(f.edges.size(), 2u);
  EXPECT_TRUE(f.edges[0].start);
  EXPECT_FALSE(f.edges[1].start);
}

TEST(IncidentTracker, ATripAfterTheSettleIsANewIncidentEvenWithoutAPoll) {
  Fed f;
  f.thermalFault(0.0, 3.0);
  f.thermalFault(3.0 + kIncidentSettleS + 1.0, 3.0);
  ASSERT_EQ(f.edges.size(), 3u);
  EXPECT_TRUE(f.edges[0].start);
  EXPECT_FALSE(f.edges[1].start);
  EXPECT_TRUE(f.edges[2].start);
  EXPECT_NE(f.edges[0].incident.id, f.edges[2].incident.id);
}

TEST(IncidentTracker, RoutineEventsOpenNothing) {
  Fed f;
  f.feed(ev(EventCode::StageChanged), 1.0);
  f.feed(ev(EventCode::FieldOff), 2.0);
  f.feed(ev(EventCode::AlarmOn), 3.0);
  f.feed(ev(EventCode::CommandApplied), 4.0);
  f.poll(100.0);
  EXPECT_TRUE(f.edges.empty());
}

TEST(IncidentTracker, AnIncidentStillTrippedEndsOnlyAfterTheJoinGap) {
  Fed f;
  f.feed(ev(EventCode::ProtectionTrip, Reason::REASON_TEMP_SUSTAINED, EventLevel::Critical), 0.0);
  f.poll(300.0);
  EXPECT_EQ(f.edges.size(), 1u) << "a protection still acting is still an incident";
  f.poll(700.0);
  ASSERT_EQ(f.edges.size(), 2u) << "ten minutes without a word ends the story (events.js JOIN_S)";
}

TEST(PushMessage, JsonHasTheIncidentsWordsAndTheRegulatorsName) {
  Fed f;
  f.thermalFault(8.0, 12.0);
  f.poll(40.0);
  ASSERT_EQ(f.edges.size(), 2u);
  const auto start = json::parse(pushMessage(f.edges[0], "Blue Heron", "json").body).as_object();
  EXPECT_EQ(start.at("event").as_string(), "start");
  EXPECT_EQ(start.at("title").as_string(), "Alternator too hot");
  EXPECT_EQ(start.at("regulator").as_string(), "Blue Heron");
  EXPECT_TRUE(start.at("end").is_null());
  EXPECT_EQ(start.at("start").as_string(), "2025-12-06T05:46:48Z");
  const PushMessage endMsg = pushMessage(f.edges[1], "Blue Heron", "json");
  const auto end = json::parse(endMsg.body).as_object();
  EXPECT_EQ(end.at("title").as_string(), "Alternator far too hot");
  EXPECT_EQ(end.at("severity").as_string(), "critical");
  EXPECT_EQ(end.at("what_to_do").as_string(), std::string(reasonWords("REASON_TEMP_CRITICAL")->action));
  EXPECT_NE(std::string(end.at("what_happened").as_string()).find("Over after 12 s."), std::string::npos);
  EXPECT_EQ(end.at("duration_s").as_double(), 12.0);
  EXPECT_EQ(endMsg.contentType, "application/json");
}

TEST(PushMessage, TextHasAnAsciiTitleHeaderAndThePlainWords) {
  Fed f;
  f.thermalFault(8.0, 12.0);
  const PushMessage m = pushMessage(f.edges[0], "Ström °1", "text");
  EXPECT_EQ(m.contentType, "text/plain; charset=utf-8");
  std::string title;
  for (const auto& [k, v] : m.headers)
    if (k == "Title") title = v;
  EXPECT_EQ(title, "Str?m  deg1: Alternator too hot");
  EXPECT_EQ(m.body.rfind("Alternator too hot (Ström °1)\n", 0), 0u) << m.body;
  EXPECT_NE(m.body.find("What to do: Check belt and airflow"), std::string::npos);
}

TEST(HaIncident, StateCarriesTheIncidentAndTheEventFires) {
  Fed f;
  f.thermalFault(8.0, 12.0);
  IntegrationSample s;
  s.valid = true;
  const IncidentWords w = incidentWords(f.edges[0]);
  auto on = json::parse(stateJson(s, &w)).as_object();
  EXPECT_EQ(on.at("incident").as_string(), "ON");
  EXPECT_EQ(on.at("incident_detail").as_object().at("title").as_string(), "Alternator too hot");
  EXPECT_EQ(json::parse(stateJson(s)).as_object().at("incident").as_string(), "OFF");
  auto fired = json::parse(incidentEventJson(f.edges[0], incidentWords(f.edges[0]))).as_object();
  EXPECT_EQ(fired.at("event_type").as_string(), "start");
  EXPECT_EQ(fired.at("what_to_do").as_string(),
            "Check belt and airflow; lower the alternator's current limit.");
}

TEST(NotifyConfig, UrlsTheSenderCanUse) {
  auto u = parseNotifyUrl("https://ntfy.sh/boat-alarms");
  ASSERT_TRUE(u);
  EXPECT_TRUE(u->tls);
  EXPECT_EQ(u->port, "443");
  EXPECT_EQ(u->target, "/boat-alarms");
  u = parseNotifyUrl("http://192.168.1.5:8123?x=1");
  ASSERT_TRUE(u);
  EXPECT_EQ(u->port, "8123");
  EXPECT_EQ(u->target, "/?x=1");
  for (const char* bad : {"ftp://h/x", "http://", "http://:80/x", "http://h:0/", "http://h:99999/",
                          "http://user:pw@h/", "http://h/a b", "ntfy.sh/topic"})
    EXPECT_FALSE(parseNotifyUrl(bad)) << bad;
}

TEST(NotifyConfig, LoaderRefusesABadUrlOrHeaderWithItsKey) {
  auto ok = loadConfigString(
      "[notify]\nurl = \"https://ntfy.sh/boat\"\nheader = \"Authorization: Bearer x\"\n", "t.toml");
  ASSERT_TRUE(ok.config);
  EXPECT_EQ(ok.config->settings.integrations.notify.format, "json");
  auto keyOf = [](const char* text) {
    auto r = loadConfigString(text, "t.toml");
    return r.config || r.errors.empty() ? std::string() : r.errors[0].key;
  };
  EXPECT_EQ(keyOf("[notify]\nurl = \"mailto:me@x\"\n"), "notify.url");
  EXPECT_EQ(keyOf("[notify]\nurl = \"http://h/\"\nheader = \"no colon\"\n"), "notify.header");
  EXPECT_EQ(keyOf("[notify]\nurl = \"http://h/\"\nheader = \"X-Bad: a\\nInjected: b\"\n"), "notify.header");
  EXPECT_EQ(keyOf("[notify]\nheader = \"Authorization: Bearer x\"\n"), "notify.url");
  EXPECT_EQ(keyOf("[notify]\nurl = \"http://h/\"\nformat = \"xml\"\n"), "notify.format");
}

}  // namespace
}  // namespace xr::integrations

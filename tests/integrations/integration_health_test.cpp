// The isolation frame's small parts (docs/integrations.md): reconnect backoff, the
// health record (one outage per loss, however many attempts), the sample.
#include "integrations/integration_health.h"

#include <gtest/gtest.h>

#include <cmath>

#include "integrations/backoff.h"
#include "integrations/integration_sample.h"

namespace xr::integrations {
namespace {

using std::chrono::milliseconds;

TEST(Backoff, DoublesUpToTheCapAndResets) {
  Backoff b(milliseconds(1000), milliseconds(5000));
  EXPECT_EQ(b.next(), milliseconds(1000));
  EXPECT_EQ(b.next(), milliseconds(2000));
  EXPECT_EQ(b.next(), milliseconds(4000));
  EXPECT_EQ(b.next(), milliseconds(5000));
  EXPECT_EQ(b.next(), milliseconds(5000));
  b.reset();
  EXPECT_EQ(b.next(), milliseconds(1000));
}

TEST(IntegrationHealth, ManyFailedAttemptsAreOneOutage) {
  const rt::WallClock clock;
  IntegrationHealth h("test", clock);
  for (int i = 0; i < 5; ++i) {
    h.attempt();
    h.failed("connection refused");
  }
  auto s = h.status();
  EXPECT_EQ(s.outages, 1u);
  EXPECT_EQ(s.connect_attempts, 5u);
  EXPECT_FALSE(s.connected);
  EXPECT_EQ(s.last_error, "connection refused");
  h.connected();
  EXPECT_TRUE(h.status().connected);
  h.failed("connection lost");
  EXPECT_EQ(h.status().outages, 2u);  // a new loss after a good connection
}

TEST(IntegrationHealth, CountsSentDroppedRefused) {
  const rt::WallClock clock;
  IntegrationHealth h("test", clock);
  h.sent(3);
  h.dropped();
  h.refused("NaN");
  h.refused("string");
  h.received(2);
  auto s = h.status();
  EXPECT_EQ(s.messages_sent, 3u);
  EXPECT_EQ(s.messages_dropped, 1u);
  EXPECT_EQ(s.values_refused, 2u);
  EXPECT_EQ(s.messages_received, 2u);
  EXPECT_EQ(s.name, "test");
  EXPECT_TRUE(s.enabled);
}

TEST(IntegrationSample, FromASnapshotInTheIntegrationsUnits) {
  rt::RuntimeSnapshot snap;
  EXPECT_FALSE(sampleOf(snap).valid);  // before the first tick
  snap.tick = 10;
  snap.telemetry.battery_v = 13.5;
  snap.telemetry.alt_a = 40.0;
  snap.telemetry.temp_f = 212.0;
  snap.telemetry.duty_pct = 55.0;
  snap.telemetry.charged_wh_lifetime = 2500.0;
  snap.telemetry.stage = ChargeStage::FLOAT;
  snap.telemetry.battery.timeToFullDischargeMin = 90.0;
  snap.telemetry.soc_pct = 80.0;
  snap.telemetry.battery.socSource = SocSource::Counted;
  auto s = sampleOf(snap);
  EXPECT_TRUE(s.valid);
  EXPECT_DOUBLE_EQ(s.alt_temp_c, 100.0);
  EXPECT_DOUBLE_EQ(s.power_w, 540.0);
  EXPECT_DOUBLE_EQ(s.charged_kwh, 2.5);
  EXPECT_DOUBLE_EQ(s.time_to_empty_s, 5400.0);
  EXPECT_EQ(s.stage, "FLOAT");
  snap.telemetry.battery.timeToFullDischargeMin = -999.0;  // the battery monitor's "unknown"
  EXPECT_LT(sampleOf(snap).time_to_empty_s, 0.0);
  // A SoC the regulator does not know yet is no number, and no time to empty.
  snap.telemetry.battery.timeToFullDischargeMin = 90.0;
  snap.telemetry.battery.socSource = SocSource::Unknown;
  EXPECT_TRUE(std::isnan(sampleOf(snap).soc_pct));
  EXPECT_LT(sampleOf(snap).time_to_empty_s, 0.0);
  snap.telemetry.battery.socSource = SocSource::OcvEstimate;
  EXPECT_DOUBLE_EQ(sampleOf(snap).soc_pct, 80.0);
  snap.telemetry.battery_v = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(std::isnan(sampleOf(snap).battery_v));  // no plausible-looking 0
  EXPECT_TRUE(std::isnan(sampleOf(snap).power_w));
}

}  // namespace
}  // namespace xr::integrations

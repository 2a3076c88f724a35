// Venus OS topics and the validation of their values (docs/integrations.md).
#include "integrations/victron_topics.h"

#include <gtest/gtest.h>

namespace xr::integrations {
namespace {

const VictronTopics kT{"c0619ab1cafe", 512};

TEST(VictronTopics, Names) {
  EXPECT_EQ(kT.topic(VictronField::MaxChargeVoltage), "N/c0619ab1cafe/battery/512/Info/MaxChargeVoltage");
  EXPECT_EQ(kT.topic(VictronField::TemperatureC), "N/c0619ab1cafe/battery/512/Dc/0/Temperature");
  EXPECT_EQ(kT.topic(VictronField::AllowToCharge), "N/c0619ab1cafe/battery/512/Io/AllowToCharge");
  EXPECT_EQ(kT.keepalive(), "R/c0619ab1cafe/keepalive");
}

TEST(VictronTopics, GoodValue) {
  auto r = decodeVictron(kT, kT.topic(VictronField::MaxChargeCurrent), R"({"value": 120.5})");
  ASSERT_TRUE(r);
  EXPECT_TRUE(r->refused.empty());
  EXPECT_TRUE(r->known);
  EXPECT_DOUBLE_EQ(r->value, 120.5);
}

TEST(VictronTopics, NullIsNoValueNotARefusal) {
  auto r = decodeVictron(kT, kT.topic(VictronField::Soc), R"({"value": null})");
  ASSERT_TRUE(r);
  EXPECT_TRUE(r->refused.empty());
  EXPECT_FALSE(r->known);
}

TEST(VictronTopics, EmptyPayloadMeansTheDeviceIsGoneNotARefusal) {
  auto r = decodeVictron(kT, kT.topic(VictronField::MaxChargeCurrent), "");
  ASSERT_TRUE(r);
  EXPECT_TRUE(r->refused.empty());
  EXPECT_TRUE(r->gone);
  EXPECT_FALSE(r->known);
}

TEST(VictronTopics, ReadRequestNames) {
  EXPECT_EQ(kT.readRequest(VictronField::MaxChargeCurrent),
            "R/c0619ab1cafe/battery/512/Info/MaxChargeCurrent");
  EXPECT_EQ(kT.readRequest(VictronField::AllowToCharge), "R/c0619ab1cafe/battery/512/Io/AllowToCharge");
}

TEST(VictronTopics, OtherTopicsAreNotOurs) {
  EXPECT_FALSE(decodeVictron(kT, "N/c0619ab1cafe/battery/513/Soc", R"({"value": 50})"));
  EXPECT_FALSE(decodeVictron(kT, "N/other/battery/512/Soc", R"({"value": 50})"));
}

TEST(VictronTopics, BadInputIsRefusedWithAReason) {
  const auto ccl = kT.topic(VictronField::MaxChargeCurrent);
  for (const char* p : {R"({"value": "12"})", R"({"value": NaN})", "NaN", " ", "[1]", R"({"v": 1})",
                        R"({"value": true})", R"({"value": -1})", R"({"value": 2000.5})"}) {
    auto r = decodeVictron(kT, ccl, p);
    ASSERT_TRUE(r) << p;
    EXPECT_FALSE(r->refused.empty()) << p;
  }
}

TEST(VictronTopics, RangesAtTheirEdges) {
  const auto cvl = kT.topic(VictronField::MaxChargeVoltage);
  EXPECT_TRUE(decodeVictron(kT, cvl, R"({"value": 70})")->refused.empty());
  EXPECT_FALSE(decodeVictron(kT, cvl, R"({"value": 70.01})")->refused.empty());
  EXPECT_TRUE(decodeVictron(kT, cvl, R"({"value": 8})")->refused.empty());
  EXPECT_FALSE(decodeVictron(kT, cvl, R"({"value": 7.99})")->refused.empty());
  const auto allow = kT.topic(VictronField::AllowToCharge);
  EXPECT_TRUE(decodeVictron(kT, allow, R"({"value": 0})")->refused.empty());
  EXPECT_FALSE(decodeVictron(kT, allow, R"({"value": 0.5})")->refused.empty());
  const auto soc = kT.topic(VictronField::Soc);
  EXPECT_TRUE(decodeVictron(kT, soc, R"({"value": 100})")->refused.empty());
  EXPECT_FALSE(decodeVictron(kT, soc, R"({"value": 100.1})")->refused.empty());
}

}  // namespace
}  // namespace xr::integrations

// BMS plausibility (docs/protections.md "BMS plausibility"): each value a BMS
// sends against the bank the regulator knows, at its threshold and just
// inside it, told once per episode within a minute and never followed
// above what either side allows.
#include "control/bms_plausibility.h"

#include <gtest/gtest.h>

#include <string>

#include "control/bms_limiter.h"

namespace xr {
namespace {

// A 24 V LiFePO4 bank: BatteryProfile lifepo4, BatteryCells 8.
Params bank24() {
  Params p;
  p.BatteryProfile = 0;
  p.BatteryCells = 8;
  p.BulkVoltage = 28.4;
  p.AbsorptionVoltage = 28.4;
  p.FloatVoltage = 27.0;
  p.BmsLimitsEnabled = true;
  return p;
}

// What a REC BMS set up for `cells` sends on that bank at `packV`.
BmsLimits rec(double packV, int cells, TimeNs stamp) {
  BmsLimits b;
  b.cvlV = cells * 3.55;
  b.cclA = 100;
  b.voltageV = packV;
  b.cellMaxV = b.cellMinV = packV / cells;
  b.source = BmsSource::Can;
  b.stamp = stamp;
  return b;
}

struct CheckRun {
  std::vector<Event> events;
  BmsPlausibility check;
  // Feeds `b` every second from `from` to `to` (s); returns the events.
  void feed(const BmsLimits& b, double packV, const Params& p, int from, int to) {
    for (int s = from; s <= to; ++s) {
      EventBatch ev;
      check.update(b, fromSec(s), packV, p, ev);
      for (std::size_t i = 0; i < ev.count; ++i) events.push_back(ev.items[i]);
    }
  }
};

TEST(BmsPlausibility, BankShapeFromCellsOrTheVoltageClass) {
  Params p = bank24();
  EXPECT_EQ(bankShape(p).cells, 8);
  EXPECT_EQ(bankShape(p).nominalV, 24);
  p.BatteryCells = 16;
  EXPECT_EQ(bankShape(p).nominalV, 48);
  Params lead;  // no cells set: the class of BulkVoltage
  lead.BatteryProfile = 1;
  lead.BatteryCells = 0;
  lead.BulkVoltage = 14.4;
  EXPECT_EQ(bankShape(lead).cells, 6);
  EXPECT_EQ(bankShape(lead).nominalV, 12);
}

TEST(BmsPlausibility, ABmsSetUpFor4CellsOnA24VBankIsToldOnceAfter10s) {
  const Params p = bank24();
  CheckRun r;
  r.feed(rec(26.0, 4, 1), 26.0, p, 0, 9);
  EXPECT_TRUE(r.events.empty());  // 9 s: not yet (a BMS starting up)
  r.feed(rec(26.0, 4, 1), 26.0, p, 10, 600);
  ASSERT_EQ(r.events.size(), 1u);  // at 10 s, and once in ten minutes
  EXPECT_EQ(r.events[0].t, fromSec(10));
  EXPECT_EQ(r.events[0].code, EventCode::BmsMismatch);
  EXPECT_EQ(r.events[0].level, EventLevel::Warning);
  EXPECT_EQ(r.check.reported(), BmsMismatch::CVL_CLASS);
  const std::string text = describe(r.events[0]);
  EXPECT_NE(text.find("14.2 V"), std::string::npos) << text;
  EXPECT_NE(text.find("24 V bank"), std::string::npos) << text;
  EXPECT_NE(text.find("set up for 8 cells?"), std::string::npos) << text;
}

TEST(BmsPlausibility, ABmsSetUpFor8CellsFitsAndSaysNothing) {
  const Params p = bank24();
  CheckRun r;
  r.feed(rec(26.0, 8, 1), 26.0, p, 0, 600);
  EXPECT_TRUE(r.events.empty());
  EXPECT_EQ(BmsPlausibility::check(rec(27.9, 8, 1), 27.9, p), BmsMismatch::NONE);
}

TEST(BmsPlausibility, CellReadingsMustFitThePackOverItsCells) {
  const Params p = bank24();
  BmsLimits b = rec(26.0, 8, 1);  // cells average 3.25 V
  b.cellMinV = 3.25 + 0.149;
  b.cellMaxV = 3.45;
  EXPECT_EQ(BmsPlausibility::check(b, 26.0, p), BmsMismatch::NONE);  // inside kCellFitV
  b.cellMinV = 3.25 + 0.151;
  EXPECT_EQ(BmsPlausibility::check(b, 26.0, p), BmsMismatch::CELL_VOLTAGE);
  // No lithium cell reads 4.6 V, whatever the pack.
  b = rec(26.0, 8, 1);
  b.cellMaxV = 4.6;
  EXPECT_EQ(BmsPlausibility::check(b, kBmsNoValue, p), BmsMismatch::CELL_VOLTAGE);
  b.cellMaxV = 4.4;
  EXPECT_EQ(BmsPlausibility::check(b, kBmsNoValue, p), BmsMismatch::NONE);
}

TEST(BmsPlausibility, APackVoltageFarFromOursAtTheClassThreshold) {
  const Params p = bank24();  // 24 V class: 2 V apart is a disagreement
  BmsLimits b = rec(26.0, 8, 1);
  b.cellMaxV = b.cellMinV = kBmsNoValue;  // a BMS without cell readings
  EXPECT_EQ(BmsPlausibility::check(b, 27.9, p), BmsMismatch::NONE);
  EXPECT_EQ(BmsPlausibility::check(b, 28.1, p), BmsMismatch::PACK_VOLTAGE);
  // With its contactor open the regulator measures the alternator's bus: not judged.
  b.chargeAllowed = false;
  EXPECT_EQ(BmsPlausibility::check(b, 28.1, p), BmsMismatch::NONE);
}

TEST(BmsPlausibility, AHighVoltageWarningWhileEveryCellReadsNormal) {
  Params p = bank24();
  p.BmsCellHighV = 3.60;  // normal under 3.50 V
  BmsLimits b = rec(26.4, 8, 1);
  b.warnings = bmswarn::HighVoltage;
  b.cellMinV = 3.28;
  b.cellMaxV = 3.49;
  EXPECT_EQ(BmsPlausibility::check(b, 26.4, p), BmsMismatch::WARNING_CELLS_NORMAL);
  b.cellMaxV = 3.51;  // a cell near full: the warning is the BMS's to give
  EXPECT_EQ(BmsPlausibility::check(b, 26.4, p), BmsMismatch::NONE);
  b.cellMaxV = 3.49;
  b.warnings = bmswarn::LowTemp;  // a temperature warning with normal cells is no contradiction
  EXPECT_EQ(BmsPlausibility::check(b, 26.4, p), BmsMismatch::NONE);
}

TEST(BmsPlausibility, TheEpisodeEndsAfterAMinuteOfFittingValues) {
  const Params p = bank24();
  CheckRun r;
  r.feed(rec(26.0, 4, 1), 26.0, p, 0, 30);
  ASSERT_EQ(r.events.size(), 1u);
  r.feed(rec(26.0, 8, 1), 26.0, p, 31, 90);  // fixed at 31 s: 59 s of fitting at 90 s
  EXPECT_EQ(r.events.size(), 1u);
  EXPECT_TRUE(r.check.active());
  r.feed(rec(26.0, 8, 1), 26.0, p, 91, 91);
  ASSERT_EQ(r.events.size(), 2u);
  EXPECT_EQ(r.events[1].level, EventLevel::Info);
  EXPECT_NE(describe(r.events[1]).find("fit the 24 V bank again"), std::string::npos);
  EXPECT_FALSE(r.check.active());
}

// The limiter obeys the BMS even when it does not fit (never above what
// either side allows), but a cell reading no cell of this bank has does not
// drive the highest cell's ceiling.
TEST(BmsPlausibility, TheLimiterObeysTheCvlAndIgnoresCellsThatDoNotFit) {
  Params p = bank24();
  p.BmsCellHighV = 3.60;
  BmsLimiter l;
  for (int s = 0; s <= 20; ++s) {
    EventBatch ev;
    l.update(rec(26.0, 4, fromSec(s)), fromSec(s), 0.0, 26.0, p, ev);
  }
  EXPECT_DOUBLE_EQ(l.cvlCeilingV(), 14.2);
  EXPECT_FALSE(l.cellHigh());
  EXPECT_EQ(l.plausibility().reported(), BmsMismatch::CVL_CLASS);
  // The same limiter on a fitting BMS whose highest cell is at the limit holds it.
  BmsLimiter fit;
  for (int s = 0; s <= 20; ++s) {
    BmsLimits b = rec(28.0, 8, fromSec(s));
    b.cellMaxV = 3.62;
    b.cellMinV = 3.48;
    EventBatch ev;
    fit.update(b, fromSec(s), 0.0, 28.0, p, ev);
  }
  EXPECT_TRUE(fit.cellHigh());
  EXPECT_FALSE(fit.plausibility().active());
}

// A Victron GX's limits (DVCC) are BmsLimits too: a GX relaying a 12 V
// BMS's 14.2 V on a 24 V bank is the same mismatch.
TEST(BmsPlausibility, AVictronGxCvlOfAnotherClassIsTheSameMismatch) {
  const Params p = bank24();
  BmsLimits gx;
  gx.cvlV = 14.2;
  gx.cclA = 50;
  gx.source = BmsSource::VictronGx;
  gx.stamp = 1;
  EXPECT_EQ(BmsPlausibility::check(gx, 26.0, p), BmsMismatch::CVL_CLASS);
  gx.cvlV = 28.2;
  EXPECT_EQ(BmsPlausibility::check(gx, 26.0, p), BmsMismatch::NONE);
}

}  // namespace
}  // namespace xr

// Plant models against published data (docs/simulator.md). Every figure
// is from the shared plant facts, by source key (docs/simulator.md lists the
// sources); each expectation is the tolerance docs/simulator.md sets.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include "drivers/sim/plant/plant.h"

namespace xr::sim {
namespace {

struct CurvePoint {
  double rpm, amps, tempC;
  double fieldA;  // < 0: full duty at kRatingV with the rotor at tempC
  double volts;
};

double modelAmps(const LundellParams& m, const CurvePoint& p) {
  const double f = p.fieldA >= 0.0 ? p.fieldA : fullFieldAmps(m, kRatingV, p.tempC);
  return outputAmps(m, p.rpm, f, p.volts, p.tempC);
}

void expectWithin10Pct(const LundellParams& m, const std::vector<CurvePoint>& pts, const char* who) {
  for (const auto& p : pts) {
    const double got = modelAmps(m, p);
    std::printf("%s %5.0f rpm %5.1f C field %5.2f A: published %6.2f A, model %6.2f A (%+.1f %%)\n", who,
                p.rpm, p.tempC, p.fieldA, p.amps, got, 100.0 * (got - p.amps) / p.amps);
    EXPECT_NEAR(got, p.amps, 0.10 * p.amps) << who << " at " << p.rpm << " rpm, " << p.tempC << " C";
  }
}

// SARA: Bosch LiX 180 A at 25 °C, 13.5 V, full field (5 A); and the six
// part-field points of docs/sources.md P2.7 (measured field, load and voltage).
TEST(PlantValidation, BoschLix180FullAndPartFieldWithin10Pct) {
  const LundellParams m = presetParams(AlternatorPreset::bosch_lix_180);
  EXPECT_NEAR(fullFieldAmps(m, kRatingV, 25.0), 5.0, 0.01);  // SARA's 5.00 A max
  expectWithin10Pct(m,
                    {{2000, 120, 25, -1, 13.5},
                     {4000, 170, 25, -1, 13.5},
                     {6000, 180, 25, -1, 13.5},
                     {1967, 36.06, 25, 1.970, 13.49},
                     {3994, 36.24, 25, 1.250, 13.54},
                     {3983, 55.65, 25, 1.650, 13.58},
                     {5992, 36.22, 25, 1.060, 13.61},
                     {5985, 56.19, 25, 1.510, 13.46},
                     {5967, 75.61, 25, 1.970, 13.58}},
                    "bosch-lix-180");
}

// WB33: Westerbeke 33A's alternator, 13.5 V: cold 24/50 A and hot 16/41/48 A
// at 1300/2500/5000 rpm. Cold = 25 °C; hot = kHotC (ARCO's hot test).
TEST(PlantValidation, Westerbeke48ColdAndHotWithin10Pct) {
  const LundellParams m = presetParams(AlternatorPreset::westerbeke_48);
  expectWithin10Pct(m,
                    {{1300, 24, 25, -1, 13.5},
                     {2500, 50, 25, -1, 13.5},
                     {1300, 16, kHotC, -1, 13.5},
                     {2500, 41, kHotC, -1, 13.5},
                     {5000, 48, kHotC, -1, 13.5}},
                    "westerbeke-48");
}

// MERC: Mercury 150 EFI, eight engine speeds into 12.6 V (belt ratio fitted
// as 2.33; temperature not published, taken as 25 °C).
TEST(PlantValidation, Mercury52EightSpeedsWithin10Pct) {
  const LundellParams m = presetParams(AlternatorPreset::mercury_52);
  std::vector<CurvePoint> pts;
  for (const auto& [rpm, a] : {std::pair{600.0, 21.0},
                               {1000.0, 37.0},
                               {1500.0, 44.0},
                               {2000.0, 48.0},
                               {2500.0, 50.0},
                               {3000.0, 51.0},
                               {4000.0, 52.0},
                               {5000.0, 52.0}})
    pts.push_back({rpm * 2.329, a, 25.0, 12.6 / (m.field_r_ohm * copperFactor(25.0)), 12.6});
  expectWithin10Pct(m, pts, "mercury-52");
}

// Hot output is lower, by more at low speed (WB33: -33 % at 1300 rpm, -18 %
// at 2500 rpm; Xantrex: up to 25 %).
TEST(PlantValidation, HotOutputLowerAndMoreSoAtLowSpeed) {
  for (auto preset : {AlternatorPreset::bosch_lix_180, AlternatorPreset::westerbeke_48}) {
    const LundellParams m = presetParams(preset);
    double lastLoss = 1.0;
    for (double rpm : {1500.0, 2500.0, 4000.0, 6000.0}) {
      const double cold = outputAmps(m, rpm, fullFieldAmps(m, kRatingV, 25.0), kRatingV, 25.0);
      const double hot = outputAmps(m, rpm, fullFieldAmps(m, kRatingV, kHotC), kRatingV, kHotC);
      const double loss = 1.0 - hot / cold;
      std::printf("%s %5.0f rpm: cold %6.1f A, hot %6.1f A, loss %.0f %%\n", toString(preset), rpm, cold, hot,
                  100 * loss);
      EXPECT_GT(loss, 0.05) << toString(preset) << " " << rpm;
      EXPECT_LT(loss, lastLoss + 1e-9) << toString(preset) << " " << rpm;
      lastLoss = loss;
    }
  }
}

// RIVAS: Ford 130 A from published parameters only. docs/sources.md P2.7
// derives the minimum field for conduction into 13.5 V + 2 x 0.9 V and a
// cut-in near 1,100 rpm at 3.6 A (linear EMF). The model must agree within
// 10 % (its bridge factor π/2 vs the table's 3√3/π differs by 5 %).
TEST(PlantValidation, Ford130KneeFieldMatchesDerivedTable) {
  const LundellParams m = presetParams(AlternatorPreset::ford_130);
  const struct {
    double rpm, fieldA;
  } table[] = {{1200, 3.30}, {1500, 2.64}, {1800, 2.20}, {2000, 1.98},
               {3000, 1.32}, {4000, 0.99}, {6000, 0.66}};
  for (const auto& r : table) {
    const double knee = kneeFieldAmps(m, r.rpm, 13.5);
    std::printf("ford-130 %5.0f rpm: knee %.2f A (table %.2f A)\n", r.rpm, knee, r.fieldA);
    EXPECT_NEAR(knee, r.fieldA, 0.10 * r.fieldA) << r.rpm;
    // Nothing below the knee, something above it.
    EXPECT_EQ(outputAmps(m, r.rpm, 0.99 * knee, 13.5, 25.0), 0.0) << r.rpm;
    EXPECT_GT(outputAmps(m, r.rpm, 1.05 * knee, 13.5, 25.0), 0.0) << r.rpm;
  }
  // Full field 3.6 A: no output at 1000 rpm (table: needs 3.96 A), some by 1200.
  EXPECT_EQ(outputAmps(m, 1000, 3.6, 13.5, 25.0), 0.0);
  EXPECT_GT(outputAmps(m, 1200, 3.6, 13.5, 25.0), 0.0);
}

// No output below the cut-in speed, nor below the knee duty at any speed,
// through the whole alternator model (field circuit included).
TEST(PlantValidation, NoOutputBelowCutInOrKneeDuty) {
  for (auto preset :
       {AlternatorPreset::bosch_lix_180, AlternatorPreset::westerbeke_48, AlternatorPreset::ford_130}) {
    const LundellParams m = presetParams(preset);
    AlternatorConfig c;
    c.preset = preset;
    c.pulley_ratio = 1.0;
    c.temp_f = c.ambient_f = 77.0;
    // Below cut-in (open-circuit 14 V at full field), even at full duty.
    const double cutIn = cutInRpm(m);
    {
      AlternatorModel a(c, m);
      for (int i = 0; i < 400; ++i) a.step(1.0, kRatingV, 0.97 * cutIn, 77.0, 0.01);
      EXPECT_EQ(a.outputAt(14.0), 0.0) << toString(preset);  // cut-in: 14 V open circuit
      EXPECT_GT(a.fieldAmps(), 0.9 * fullFieldAmps(m, kRatingV, 25.0));
    }
    for (double rpm : {1500.0, 2500.0, 4000.0, 6000.0}) {
      const double kneeDuty = kneeFieldAmps(m, rpm, 13.5) * m.field_r_ohm * copperFactor(25.0) / kRatingV;
      if (kneeDuty >= 1.0) continue;
      for (double duty : {0.97 * kneeDuty, 1.1 * kneeDuty}) {
        AlternatorModel a(c, m);
        for (int i = 0; i < 400; ++i) a.step(duty, kRatingV, rpm, 77.0, 0.01);
        const double amps = a.outputAt(13.5);
        if (duty < kneeDuty)
          EXPECT_EQ(amps, 0.0) << toString(preset) << " " << rpm << " duty " << duty;
        else
          EXPECT_GT(amps, 0.0) << toString(preset) << " " << rpm << " duty " << duty;
      }
    }
  }
}

}  // namespace
}  // namespace xr::sim

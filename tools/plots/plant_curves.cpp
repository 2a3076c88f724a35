// Runs the simulator's plant models and writes their curves as CSV files for
// tools/plots/plot_plant.py (docs/simulator.md's plots): alternator output
// against speed (hot and cold), the knee, OCV, charge tapers with rest,
// alternator warm-up and a load dump.
//   xr_plant_curves <output directory>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "drivers/sim/plant/plant.h"

using namespace xr::sim;

namespace {

void alternatorCurves(std::ofstream& f) {
  f << "preset,temp_c,rpm,amps\n";
  for (auto p :
       {AlternatorPreset::bosch_lix_180, AlternatorPreset::westerbeke_48, AlternatorPreset::ford_130}) {
    const LundellParams m = presetParams(p);
    for (double t : {25.0, kHotC})
      for (double rpm = 0; rpm <= 7000; rpm += 25)
        f << toString(p) << ',' << t << ',' << rpm << ','
          << outputAmps(m, rpm, fullFieldAmps(m, kRatingV, t), kRatingV, t) << '\n';
  }
}

void mercuryCurve(std::ofstream& f) {
  f << "engine_rpm,amps\n";
  const LundellParams m = presetParams(AlternatorPreset::mercury_52);
  for (double rpm = 0; rpm <= 6000; rpm += 25)
    f << rpm << ',' << outputAmps(m, rpm * 2.329, 12.6 / (m.field_r_ohm * copperFactor(25.0)), 12.6, 25.0)
      << '\n';
}

void kneeCurve(std::ofstream& f) {
  f << "preset,rpm,knee_field_a\n";
  for (auto p : {AlternatorPreset::bosch_lix_180, AlternatorPreset::ford_130}) {
    const LundellParams m = presetParams(p);
    for (double rpm = 800; rpm <= 7000; rpm += 25) {
      const double k = kneeFieldAmps(m, rpm, 13.5);
      if (k < 10) f << toString(p) << ',' << rpm << ',' << k << '\n';
    }
  }
}

void ocvCurves(std::ofstream& f) {
  f << "chemistry,soc_pct,cell_v\n";
  for (auto c : {Chemistry::lifepo4, Chemistry::agm, Chemistry::flooded}) {
    BatteryConfig bc;
    bc.chemistry = c;
    bc.capacity_ah = 100;
    BatteryModel b(bc);
    for (double s = 0; s <= 100.0001; s += 0.5) {
      b.setSocPct(s);
      f << toString(c) << ',' << s << ',' << b.terminalVolts(0.0) / b.cells() << '\n';
    }
  }
}

// CC-CV charge from socPct, then rest; one row per 10 s.
void chargeAndRest(std::ofstream& f, const char* label, Chemistry c, double cap, double socPct, double amps,
                   double cv, double tail, double restS) {
  BatteryConfig bc;
  bc.chemistry = c;
  bc.capacity_ah = cap;
  bc.soc_pct = socPct;
  BatteryModel b(bc);
  const double dt = 0.1;
  bool charging = true;
  double restStart = -1;
  for (long n = 0;; ++n) {
    const double t = n * dt;
    double i = 0.0;
    if (charging) {
      i = std::min(amps, (cv - b.emf()) / b.seriesR());
      if (i < amps && i <= tail) charging = false, restStart = t;
    }
    if (!charging) i = 0.0;
    if (n % 100 == 0)
      f << label << ',' << t << ',' << b.terminalVolts(i) << ',' << i << ',' << b.socPct() << ','
        << (charging ? 1 : 0) << '\n';
    if ((!charging && t - restStart > restS) || t > 24 * 3600) break;
    b.step(i, dt);
  }
}

void thermal(std::ofstream& f) {
  f << "t_s,stator_c,case_c,amps\n";
  AlternatorConfig c;
  c.pulley_ratio = 1.0;
  c.temp_f = c.ambient_f = 77.0;
  AlternatorModel a(c);
  for (int i = 0; i <= 3 * 3600; ++i) {
    if (i % 30 == 0) f << i << ',' << a.statorC() << ',' << a.caseC() << ',' << a.amps() << '\n';
    a.step(1.0, 13.5, 3000.0, 77.0, 1.0);
    a.setOutput(a.outputAt(13.5));
  }
}

void loadDump(std::ofstream& f) {
  // plant_test.cpp's ISO 16750-2 test A case.
  f << "t_ms,bus_v,alt_a,field_a\n";
  PlantConfig c;
  c.alternator.pulley_ratio = 1.0;
  c.alternator.temp_f = c.alternator.ambient_f = 77.0;
  c.rpm = 6000;
  c.house_a = 10;
  c.tvs_clamp_v = 200;
  c.battery.soc_pct = 30;
  Plant p(c);
  for (int i = 0; i < 2000; ++i) p.step(1.0, 0.0025);
  for (int i = -40; i < 1000; ++i) {
    if (i == 0) p.setBmsConnected(false);
    p.step(i < 0 ? 1.0 : 0.0, 0.0005);
    f << i * 0.5 << ',' << p.truth().battery_v << ',' << p.truth().alt_a << ',' << p.truth().field_a << '\n';
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s <output directory>\n", argv[0]);
    return 64;
  }
  const std::filesystem::path dir = argv[1];
  std::filesystem::create_directories(dir);
  std::ofstream alt(dir / "alternator.csv"), knee(dir / "knee.csv"), ocv(dir / "ocv.csv"),
      charge(dir / "charge.csv"), th(dir / "thermal.csv"), ld(dir / "load_dump.csv");
  alternatorCurves(alt);
  std::ofstream merc(dir / "mercury.csv");
  mercuryCurve(merc);
  kneeCurve(knee);
  ocvCurves(ocv);
  charge << "run,t_s,volts,amps,soc_pct,charging\n";
  chargeAndRest(charge, "agm_0.2C", Chemistry::agm, 95.69, 50, 0.2 * 95.69, 14.4, 0.005 * 95.69, 12 * 3600);
  chargeAndRest(charge, "agm_0.4C", Chemistry::agm, 95.69, 50, 0.4 * 95.69, 14.4, 0.005 * 95.69, 12 * 3600);
  chargeAndRest(charge, "lfp_0.5C", Chemistry::lifepo4, 100, 45, 50, 14.2, 2.0, 2 * 3600);
  thermal(th);
  loadDump(ld);
  return 0;
}

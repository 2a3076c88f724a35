#include "drivers/sim/plant/lundell.h"

#include <cmath>
#include <cstring>
#include <initializer_list>
#include <limits>

namespace xr::sim {
namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kV1PerVdc = 1.4142135623730951 / kPi;  // fundamental phase rms per bridge DC volt
constexpr double kIdcPerIph = 3.0 * kV1PerVdc;          // power balance through the bridge
double electricalRadS(const LundellParams& m, double rpm) { return m.pole_pairs * 2.0 * kPi * rpm / 60.0; }
}  // namespace

const char* toString(AlternatorPreset p) {
  switch (p) {
    case AlternatorPreset::bosch_lix_180:
      return "bosch-lix-180";
    case AlternatorPreset::westerbeke_48:
      return "westerbeke-48";
    case AlternatorPreset::ford_130:
      return "ford-130";
    case AlternatorPreset::mercury_52:
      return "mercury-52";
  }
  return "?";
}

bool parseAlternatorPreset(const char* name, AlternatorPreset& out) {
  for (auto p :
       {AlternatorPreset::bosch_lix_180, AlternatorPreset::westerbeke_48, AlternatorPreset::ford_130}) {
    if (std::strcmp(toString(p), name) == 0) {
      out = p;
      return true;
    }
  }
  return false;
}

LundellParams presetParams(AlternatorPreset p) {
  LundellParams m;  // defaults: bosch-lix-180
  switch (p) {
    case AlternatorPreset::bosch_lix_180:
      // Bosch LiX 180 A / 2.4 kW (docs/sources.md SARA): 8 pole pairs, copper
      // 30 mΩ at 20 °C, field 5.0 A max at 13.5 V (2.70 Ω at 25 °C: winding
      // 1.90 Ω + brushes and driver), L_f 0.2 H. flux_k, flux_sat_a,
      // stator_l_h and stator_rx_ohm are fitted (tools/plots/fit_alternators.py)
      // to the 25 °C full-field curve (120/170/180 A at 2000/4000/6000 rpm)
      // and the six part-field points of §2.7.
      break;
    case AlternatorPreset::westerbeke_48:
      // Westerbeke 33A's 48 A alternator (docs/sources.md WB33): cold 24/50 A and
      // hot 16/41/48 A at 1300/2500/5000 rpm, 13.5 V. Not published, so
      // assumed: 6 pole pairs, the XEN field circuit (12.83 V / 4.2 A =
      // 3.05 Ω), SARA's L_f/R_f (0.105 s). Fitted: flux, L_s and the stator
      // resistance (all of it taken as copper, so it follows temperature).
      m.pole_pairs = 6.0;
      m.flux_k = 0.0086238;
      m.flux_sat_a = 1.84167;
      m.stator_l_h = 268.21e-6;
      m.stator_rx_ohm = 0.0;
      m.copper_r_ohm = 0.060086;
      m.field_r_ohm = 3.05;
      m.field_l_h = 0.32;
      break;
    case AlternatorPreset::ford_130:
      // Ford 130 A (docs/sources.md RIVAS), published parameters only, no fit:
      // 6 pole pairs, k_e 3.72 mV·s/A, no saturation data (linear), L_s
      // 120 µH, R_s 37 mΩ, 3.6 A max field (3.75 Ω at 13.5 V, DERIVED),
      // V_d 0.9 V as in the §2.7 knee table. L_f/R_f assumed SARA's 0.105 s.
      m.pole_pairs = 6.0;
      m.flux_k = 0.003722;
      m.flux_sat_a = 1.0e4;
      m.stator_l_h = 120e-6;
      m.stator_rx_ohm = 0.0;
      m.copper_r_ohm = 0.037;
      m.field_r_ohm = 3.75;
      m.field_l_h = 0.39;
      m.diode_v = 0.9;
      break;
    case AlternatorPreset::mercury_52:
      // Mercury 150 EFI alternator (docs/sources.md MERC): 21/37/44/48/50/51/52/
      // 52 A at 600-5000 engine rpm into 12.6 V, temperature not stated (taken
      // as 25 °C), belt ratio not given. Assumed 6 pole pairs and the XEN field
      // circuit; fitted (tools/plots/fit_alternators.py) flux, L_s, the
      // (copper) stator resistance and the belt ratio: 2.33, inside the
      // "2-3 x crankshaft" of WIKI-ALT. Shaft rpm = engine rpm x 2.33.
      m.pole_pairs = 6.0;
      m.flux_k = 0.01669;
      m.flux_sat_a = 1.18902;
      m.stator_l_h = 356.28e-6;
      m.stator_rx_ohm = 0.0;
      m.copper_r_ohm = 0.297224;
      m.field_r_ohm = 3.05;
      m.field_l_h = 0.32;
      break;
  }
  return m;
}

double fluxLinkage(const LundellParams& m, double fieldA) {
  return m.flux_k * m.flux_sat_a * std::tanh(fieldA / m.flux_sat_a);
}

double outputAmps(const LundellParams& m, double altRpm, double fieldA, double terminalV, double tC) {
  const double we = electricalRadS(m, altRpm);
  const double e = we * fluxLinkage(m, fieldA) / 1.4142135623730951;
  const double v1 = kV1PerVdc * (terminalV + 2.0 * m.diode_v);
  if (e <= v1) return 0.0;
  const double r = m.stator_rx_ohm + m.copper_r_ohm * copperFactor(tC);
  const double x = we * m.stator_l_h;
  const double z2 = r * r + x * x;
  const double s = std::sqrt(z2 * e * e - x * x * v1 * v1);
  return kIdcPerIph * (s - v1 * r) / z2;
}

double openCircuitVolts(const LundellParams& m, double altRpm, double fieldA) {
  const double e = electricalRadS(m, altRpm) * fluxLinkage(m, fieldA) / 1.4142135623730951;
  return e / kV1PerVdc - 2.0 * m.diode_v;
}

double kneeFieldAmps(const LundellParams& m, double altRpm, double terminalV) {
  const double we = electricalRadS(m, altRpm);
  if (we <= 0.0) return std::numeric_limits<double>::infinity();
  const double lambda = kV1PerVdc * (terminalV + 2.0 * m.diode_v) * 1.4142135623730951 / we;
  const double x = lambda / (m.flux_k * m.flux_sat_a);
  if (x >= 1.0) return std::numeric_limits<double>::infinity();
  return m.flux_sat_a * std::atanh(x);
}

double cutInRpm(const LundellParams& m) {
  // Open-circuit voltage is linear in speed: solve for 14 V directly.
  const double ifull = fullFieldAmps(m, kRatingV, 25.0);
  const double per1000 = openCircuitVolts(m, 1000.0, ifull) + 2.0 * m.diode_v;  // before the diodes
  return 1000.0 * (14.0 + 2.0 * m.diode_v) / per1000;
}

}  // namespace xr::sim

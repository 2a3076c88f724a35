#pragma once
// The electrical side of a Lundell (claw-pole) alternator, as in the
// published reduced models (docs/simulator.md "Alternator"; docs/sources.md P2.1):
//   field:   v_f = R_f(T)·i_f + L_f·di_f/dt
//   flux:    λ(i_f) = k·i_sat·tanh(i_f / i_sat)   (saturation, SARA's k_e(i_f))
//   EMF:     E = ω_e·λ / √2 per phase (rms), ω_e = pole pairs × shaft rad/s
//   output:  each phase is E behind R_s(T) + jω_e·L_s into a diode bridge
//            whose DC side sits at the terminal voltage plus two diode drops;
//            on the fundamental, the bridge input is V1 = (√2/π)·(V + 2·V_d)
//            in phase with the current, so
//              E² = (V1 + R_s·I)² + (ω_e·L_s·I)²,   I_dc = (3√2/π)·I.
// Below the knee (E <= V1) nothing flows; at high speed I tends to
// λ/(√2·L_s), a current limit set by the field: the curve flattens.
namespace xr::sim {

inline constexpr double kCopperAlpha = 0.00393;  // 1/K at 20 °C (docs/sources.md CU)
inline constexpr double kHotC = 150.0;           // "hot" windings: ARCO's stator at 305 °F in its hot test
inline constexpr double kRatingV = 13.5;         // test voltage of published curves (SARA, WB33, BALC)
inline constexpr double kMaxAltRpm = 18000.0;    // highest rated shaft speed (docs/sources.md HYU, KIA)

struct LundellParams {
  double pole_pairs = 8.0;
  double flux_k = 0.0054116;       // V·s/A: peak flux linkage per field amp at low field
  double flux_sat_a = 6.7837;      // field current scale of the saturation (tanh)
  double stator_l_h = 117.41e-6;   // synchronous inductance per phase
  double stator_rx_ohm = 0.12329;  // fitted series resistance that does not follow temperature
  double copper_r_ohm =
      0.030;  // stator copper per phase at 20 °C (follows kCopperAlpha; carries the I²R heat)
  double field_r_ohm = 2.648;  // field circuit (winding + brushes) at 20 °C
  double field_l_h = 0.2;
  double diode_v = 1.0;  // per rectifier diode
  // Two-node thermal model (stator+rotor windings, case): J/K and W/K.
  double stator_c_j_k = 6000.0;
  double case_c_j_k = 24000.0;
  double stator_case_g_w_k = 12.0;
  double case_air_g_w_k = 15.0;  // at kFanRefRpm; scales with speed (fan)
};

inline constexpr double kFanRefRpm = 3000.0;  // shaft rpm of the thermal calibration (ARCO's hot test)

enum class AlternatorPreset { bosch_lix_180, westerbeke_48, ford_130, mercury_52 };
const char* toString(AlternatorPreset p);
bool parseAlternatorPreset(const char* name, AlternatorPreset& out);
LundellParams presetParams(AlternatorPreset p);

// Resistance multiplier of copper at t °C.
inline double copperFactor(double tC) { return 1.0 + kCopperAlpha * (tC - 20.0); }

double fluxLinkage(const LundellParams& m, double fieldA);
// DC output into `terminalV` at `altRpm` with `fieldA` and windings at tC.
double outputAmps(const LundellParams& m, double altRpm, double fieldA, double terminalV, double tC);
// Open-circuit DC voltage (after the two diode drops) at altRpm and fieldA.
double openCircuitVolts(const LundellParams& m, double altRpm, double fieldA);
// Field current needed before any current flows into terminalV (the knee);
// +inf when even unbounded field would not do it (it always does: the flux
// saturates at k·i_sat, so: +inf above that).
double kneeFieldAmps(const LundellParams& m, double altRpm, double terminalV);
// Full-duty field current at `fieldV` with the rotor at tC.
inline double fullFieldAmps(const LundellParams& m, double fieldV, double tC) {
  return fieldV / (m.field_r_ohm * copperFactor(tC));
}
// Lowest shaft rpm at which the machine, cold (25 °C) at full duty from
// kRatingV, opens to 14 V (the cut-in test: docs/sources.md P2.6.2).
double cutInRpm(const LundellParams& m);

}  // namespace xr::sim

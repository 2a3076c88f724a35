#pragma once
// A small deterministic first-order plant for closed-loop control tests
// (the real simulator lives in drivers/sim/). Alternator current follows
// duty x ampsPerPct with time constant tau; the battery is an open-circuit
// voltage that integrates net current plus an internal resistance.
#include <algorithm>
#include <cmath>

namespace xr::test {

struct Plant {
  double tau = 0.15;               // s, field time constant
  double ampsPerPct = 1.0;         // A per % duty at this RPM
  double deadTime = 0.0;           // s, transport delay of the duty (SystemID tests)
  double Ialt = 0.0;               // A
  double house = 5.0;              // A drawn by the house
  double Vocv = 13.0;              // V
  double R = 0.01;                 // ohm
  double voltsPerAmpSec = 0.0005;  // dVocv/dt per net amp (a small bank so CV tests run in seconds)
  double VocvMax = 14.8;           // the bank saturates here
  double kneePct = 0.0;            // duty under which no current flows (a Lundell machine's knee)
  // Delay line for deadTime (fixed size, no allocation).
  double delayed[4096] = {};
  int head = 0, len = 0;

  double Ibat() const { return Ialt - house; }
  double V() const { return Vocv + R * Ibat(); }

  void advance(double dutyPct, bool field, double dt) {
    double u = field ? dutyPct : 0.0;
    if (deadTime > 0.0) {
      const int n = std::clamp(static_cast<int>(std::lround(deadTime / dt)), 1, 4095);
      delayed[head] = u;
      head = (head + 1) % 4096;
      len = std::min(len + 1, 4096);
      u = len > n ? delayed[(head - 1 - n + 4096) % 4096] : 0.0;
    }
    const double target = std::max(0.0, u - kneePct) * ampsPerPct;
    Ialt += (target - Ialt) * std::min(1.0, dt / tau);
    Vocv = std::min(VocvMax, Vocv + Ibat() * voltsPerAmpSec * dt);
  }
};

}  // namespace xr::test

// Fit of the lead-acid end-of-charge constants in drivers/sim/plant/battery.cpp
// (b, g0, m, eps) to Rod Collins' Lifeline GPL-31T tests (docs/sources.md MS):
// 14.4 V reached at 63.3 % SoC at 0.4C and 77.4 % at 0.2C from 50 %, full
// (0.5 % C tail) after ~5.5 h at 0.2C; g0 is tied to b, m, eps by a steady
// current at full of 0.4 % C (below the 0.5 % C "full" criterion).
// The battery dynamics are copied from battery.cpp (25 °C).
//   g++ -O2 -std=c++20 tools/plots/fit_agm_taper.cpp -o /tmp/fit && /tmp/fit
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>
struct P {
  double b, g0, m, eps;
};
const double T[5][2] = {{0, 10.5 / 6}, {.25, 11.75 / 6}, {.5, 12.2 / 6}, {.75, 12.55 / 6}, {1, 12.8 / 6}};
double ocv(double s) {
  for (int i = 1; i < 5; i++)
    if (s <= T[i][0])
      return T[i - 1][1] + (s - T[i - 1][0]) * (T[i][1] - T[i - 1][1]) / (T[i][0] - T[i - 1][0]);
  return T[4][1];
}
struct R {
  double hit = -1, socHit = -1, end = -1;
};
R sim(P p, double cap, double I0, double tail, double dt = 0.1) {
  double R0 = 0.5 / cap, soc = 0.5, v1 = 0, v2 = 0;
  R r;
  double k1 = 1 - exp(-dt / 60), k2 = 1 - exp(-dt / 7200);
  for (double t = 0; t < 14 * 3600; t += dt) {
    double E = 6 * ocv(soc) + v1 + v2;
    double I = std::min(I0, (14.4 - E) / R0);
    if (I < I0 && r.hit < 0) {
      r.hit = t;
      r.socHit = soc;
    }
    if (r.hit >= 0 && I <= tail) {
      r.end = t;
      return r;
    }
    double g = p.g0 * cap * pow(1 - soc + p.eps, p.m);
    double eta = 6 * p.b * log1p(std::max(I, 0.0) / g);
    v1 += (0.5 * R0 * I + 0.8 * eta - v1) * k1;
    v2 += (1.0 * R0 * I + 0.2 * eta - v2) * k2;
    soc = std::min(1.0, soc + I * dt * 0.95 / (cap * 3600));
  }
  return r;
}
P mk(const std::array<double, 3>& x) {  // g0 from: steady current at full = 0.004 C
  P p{x[0], 0, x[1], x[2]};
  double eta = (14.4 - 12.8 - 0.004 * 95.69 * 0.5 / 95.69 * 2.5) / 6;
  p.g0 = 0.004 / (exp(eta / p.b) - 1) / pow(p.eps, p.m);
  return p;
}
double err(const std::array<double, 3>& x) {
  if (x[0] <= 0.005 || x[1] <= 0.05 || x[2] <= 0.001) return 1e9;
  P p = mk(x);
  double cap = 95.69;
  R a = sim(p, cap, 0.4 * cap, 0.005 * cap, 0.5), b = sim(p, cap, 0.2 * cap, 0.005 * cap, 0.5);
  if (a.hit < 0 || b.hit < 0 || b.end < 0) return 1e6;
  return pow((a.socHit - 0.633) / 0.03, 2) + pow((b.socHit - 0.774) / 0.03, 2) +
         pow((b.end / 3600 - 5.5) / 0.3, 2);
}
int main() {
  std::vector<std::array<double, 3>> s = {
      {0.08, 0.8, 0.02}, {0.1, 0.8, 0.02}, {0.08, 1.2, 0.02}, {0.08, 0.8, 0.05}};
  std::vector<double> v;
  for (auto& x : s) v.push_back(err(x));
  for (int it = 0; it < 150; it++) {
    int n = 3;
    std::vector<int> o = {0, 1, 2, 3};
    std::sort(o.begin(), o.end(), [&](int a, int b) { return v[a] < v[b]; });
    auto S = s;
    auto V = v;
    for (int i = 0; i < 4; i++) {
      s[i] = S[o[i]];
      v[i] = V[o[i]];
    }
    std::array<double, 3> c{};
    for (int i = 0; i < n; i++)
      for (int j = 0; j < 3; j++) c[j] += s[i][j] / n;
    auto lerp = [&](double f) {
      std::array<double, 3> r;
      for (int j = 0; j < 3; j++) r[j] = c[j] + f * (s[3][j] - c[j]);
      return r;
    };
    auto r = lerp(-1);
    double fr = err(r);
    if (fr < v[0]) {
      auto e = lerp(-2);
      double fe = err(e);
      if (fe < fr) {
        s[3] = e;
        v[3] = fe;
      } else {
        s[3] = r;
        v[3] = fr;
      }
    } else if (fr < v[2]) {
      s[3] = r;
      v[3] = fr;
    } else {
      auto k = lerp(0.5);
      double fk = err(k);
      if (fk < v[3]) {
        s[3] = k;
        v[3] = fk;
      } else
        for (int i = 1; i < 4; i++) {
          for (int j = 0; j < 3; j++) s[i][j] = s[0][j] + 0.5 * (s[i][j] - s[0][j]);
          v[i] = err(s[i]);
        }
    }
  }
  int b = std::min_element(v.begin(), v.end()) - v.begin();
  P p = mk(s[b]);
  double cap = 95.69;
  R a = sim(p, cap, 0.4 * cap, 0.005 * cap, 0.1), c = sim(p, cap, 0.2 * cap, 0.005 * cap, 0.1);
  printf("b %.5f g0 %.6g m %.5f eps %.6g err %.4f | 0.4C hit %.3f | 0.2C hit %.3f end %.2f h\n", p.b, p.g0,
         p.m, p.eps, v[b], a.socHit, c.socHit, c.end / 3600);
}

// regulator_trace_digest: a bit-exact digest of every Outputs field (duty,
// field, buzzer, INA requests, every event and the whole telemetry, NaN
// normalised) over five closed-loop scenarios. Run it before and after a
// change to the core that must not change behaviour (a speed-up): the
// digests must be identical. Not a test: a digest is no golden value, only
// a before/after comparison.
// Usage: regulator_trace_digest
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <type_traits>

#include "../../unit/control/reg_rig.h"

namespace {

using namespace xr;

// FNV-1a over the bytes of each value, in visiting order.
struct Digest {
  std::uint64_t h = 1469598103934665603ull;
  long ticks = 0;

  void bytes(const void* p, std::size_t n) {
    const auto* c = static_cast<const unsigned char*>(p);
    for (std::size_t i = 0; i < n; ++i) {
      h ^= c[i];
      h *= 1099511628211ull;
    }
  }
  template <typename T>
  void operator()(const char*, const T& v) {
    if constexpr (std::is_same_v<T, double>) {
      const double d = std::isnan(v) ? std::numeric_limits<double>::quiet_NaN() : v;
      bytes(&d, sizeof d);
    } else if constexpr (std::is_same_v<T, bool>) {
      const unsigned char b = v ? 1 : 0;
      bytes(&b, 1);
    } else {
      const long x = static_cast<long>(v);
      bytes(&x, sizeof x);
    }
  }
  void add(const Outputs& o) {
    Digest& d = *this;
    d("", o.dutyPct), d("", o.fieldEnable), d("", o.buzzer), d("", o.inaFastMode), d("", o.inaBovlVolts);
    d("", static_cast<long>(o.events.count)), d("", static_cast<long>(o.events.dropped));
    for (std::size_t i = 0; i < o.events.count; ++i) {
      const Event& e = o.events.items[i];
      d("", e.t), d("", e.level), d("", e.code), d("", e.reason), d("", e.mode), d("", e.a), d("", e.b),
          d("", e.detail);
    }
    const Telemetry& t = o.telemetry;
    d("", t.now), d("", t.mode), d("", t.stage), d("", t.reason);
    visitTelemetryColumns(t, t.now, [&](const char*, const ColumnValue& v) {
      if (const double* x = std::get_if<double>(&v)) d("", *x);
      if (const bool* b = std::get_if<bool>(&v)) d("", *b);
    });
    visitControlTelemetry(t.control, d);
    visitProtectionTelemetry(t.protection, d);
    visitBatteryTelemetry(t.battery, d);
    ++ticks;
  }
  void print(const char* name, const Outputs& last) const {
    std::printf("%-12s %016llx ticks %ld final duty %.6f\n", name, static_cast<unsigned long long>(h), ticks,
                last.dutyPct);
  }
};

// The three benchmark workloads, prepare phase included.
void benchScenario(const char* name, int sc) {
  Params p;
  if (sc == 1) {
    p.bulkVoltageHoldMs = 1000;
    p.AbsorptionTimeoutMs = 86400000;
    p.absorptionCompleteTime = 3600000;
  }
  test::RegRig r(p);
  Digest d;
  if (sc != 1) r.plant.voltsPerAmpSec = 0.0;
  if (sc == 1) {
    r.plant.Vocv = 14.35;
    r.plant.VocvMax = 14.39;
    r.plant.house = 30.0;
  }
  for (long i = 0; i < 40000; ++i) {
    if (sc == 2) {
      const long k = i % 2800;
      if (k == 0) r.reg.command({CommandType::Off, 0.0, false});
      if (k == 2400) r.reg.command({CommandType::Auto, 0.0, false});
    }
    r.tick();
    d.add(*r.out);
  }
  d.print(name, *r.out);
}

// A charge through the stages with CH1 not fresh on some ticks, moving RPM
// and temperature, manual, load steps, Limp Home, setParams and an RPM cut.
void chargeScenario() {
  Params p;
  p.bulkVoltageHoldMs = 2000;
  p.absorptionCompleteTime = 5000;
  p.AbsorptionTimeoutMs = 60000;
  test::RegRig r(p);
  Digest d;
  r.plant.voltsPerAmpSec = 0.002;
  r.plant.house = 10;
  for (long i = 0; i < 200000; ++i) {
    r.ch1Fresh = (i % 2) == 0 || (i % 7) == 0;
    r.rpm =
        1500 + 800 * std::sin(static_cast<double>(i) * 0.0007) + static_cast<double>((i * 7919) % 13) * 0.3;
    r.tempF = 100 + static_cast<double>(i) * 0.0012;
    if (i == 60000) r.reg.command({CommandType::Manual, 35.0, false});
    if (i == 64000) r.reg.command({CommandType::Auto, 0.0, false});
    if (i == 90000) r.plant.house = 80;
    if (i == 120000) r.plant.Vocv = 12.5;
    if (i == 150000) r.reg.command({CommandType::LimpHome, 0.0, false});
    if (i == 155000) r.reg.command({CommandType::LimpHomeOff, 0.0, false});
    if (i == 170000) {
      Params q = p;
      q.MaxDuty = 60;
      q.PidKp = 0.2;
      q.TempSource = 1;
      r.reg.setParams(q);
    }
    if (i == 180000) r.rpm = 100;
    r.tick();
    d.add(*r.out);
  }
  d.print("charge", *r.out);
}

// Rising temperature and an over-voltage bank, re-enable, TargetVoltageMode.
void faultScenario() {
  Params p;
  test::RegRig r(p);
  Digest d;
  r.plant.voltsPerAmpSec = 0.01;
  r.plant.VocvMax = 16.0;
  for (long i = 0; i < 120000; ++i) {
    r.tempF = 100 + static_cast<double>(i) * 0.003;
    if (i == 40000) r.reg.command({CommandType::ReenableField, 0.0, false});
    if (i == 70000) {
      Params q = p;
      q.TargetVoltageMode = 1;
      q.TargetVoltageSetpoint = 13.8;
      q.IgnoreTemperature = 1;
      r.reg.setParams(q);
    }
    r.tick();
    d.add(*r.out);
  }
  d.print("faults", *r.out);
}

}  // namespace

int main() {
  benchScenario("bulk", 0);
  benchScenario("absorption", 1);
  benchScenario("shutdown", 2);
  chargeScenario();
  faultScenario();
  return 0;
}

// Zero heap allocations in Regulator::step over 100,000 ticks. The global
// operator new is replaced in THIS executable only and counts while armed.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "reg_rig.h"

// Our operator new is malloc-backed, so free() in operator delete matches;
// GCC cannot see that through the replacement.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

namespace {
std::atomic<bool> g_armed{false};
std::atomic<long> g_allocs{0};
}  // namespace

void* operator new(std::size_t n) {
  if (g_armed.load(std::memory_order_relaxed)) g_allocs.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) { return operator new(n); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace xr {
namespace {

TEST(RegulatorAlloc, CounterSeesAnAllocation) {
  g_allocs = 0;
  g_armed = true;
  auto* p = new int(3);
  g_armed = false;
  delete p;
  EXPECT_EQ(g_allocs.load(), 1);  // the counter works, so a 0 below means something
}

TEST(RegulatorAlloc, ZeroHeapAllocationsOver100000Ticks) {
  Params p;
  p.bulkVoltageHoldMs = 2000;
  p.absorptionCompleteTime = 2000;
  test::RegRig r(p);
  r.plant.Vocv = 14.3;
  r.plant.VocvMax = 14.38;
  r.run(0.5);  // construction and first ticks outside the count
  g_allocs = 0;
  g_armed = true;
  for (int i = 0; i < 100000; ++i) {
    // Cover bulk, absorption (CV), a shutdown ramp, the RPM cut and commands.
    if (i == 40000) r.reg.command({CommandType::Off, 0.0, false});
    if (i == 60000) r.reg.command({CommandType::Auto, 0.0, false});
    if (i == 70000) r.rpm = 50.0;
    if (i == 75000) r.rpm = 2000.0;
    if (i == 80000) r.reg.command({CommandType::LimpHome, 0.0, false});
    if (i == 90000) r.reg.command({CommandType::LimpHomeOff, 0.0, false});
    r.tick();
  }
  g_armed = false;
  EXPECT_EQ(g_allocs.load(), 0);
}

}  // namespace
}  // namespace xr

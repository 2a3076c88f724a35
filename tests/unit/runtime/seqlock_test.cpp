#include "core/seqlock.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <thread>

#include "control/telemetry.h"

namespace xr::rt {
namespace {

TEST(SeqLock, ReturnsLastStoredValueAndGrowsVersion) {
  SeqLock<Telemetry> s;
  const auto v0 = s.version();
  Telemetry t;
  t.ibv_v = 13.8;
  t.mode = FieldControlMode::MODE_LIMP_HOME;
  t.control.cv_I = 4.25;
  s.store(t);
  Telemetry out;
  const auto v1 = s.load(out);
  EXPECT_GT(v1, v0);
  EXPECT_DOUBLE_EQ(out.ibv_v, 13.8);
  EXPECT_EQ(out.mode, FieldControlMode::MODE_LIMP_HOME);
  EXPECT_DOUBLE_EQ(out.control.cv_I, 4.25);
  t.ibv_v = 14.1;
  s.store(t);
  EXPECT_DOUBLE_EQ(s.load().ibv_v, 14.1);  // newest wins
  EXPECT_GT(s.version(), v1);
}

// Every byte survives the word-by-word store, also in a last partial word
// (sizes 1, 8, 13 and 4101 bytes).
template <std::size_t N>
struct Bytes {
  unsigned char b[N];
};
template <std::size_t N>
void roundTrips() {
  SeqLock<Bytes<N>> s;
  Bytes<N> in;
  for (std::size_t i = 0; i < N; ++i) in.b[i] = static_cast<unsigned char>(i * 37 + 11);
  s.store(in);
  const Bytes<N> out = s.load();
  for (std::size_t i = 0; i < N; ++i) EXPECT_EQ(out.b[i], in.b[i]) << "byte " << i << " of " << N;
}
TEST(SeqLock, EveryByteRoundTripsWhateverTheSize) {
  roundTrips<1>();
  roundTrips<8>();
  roundTrips<13>();
  roundTrips<4101>();
}

// Payload whose fields must always agree: a torn read would show a mismatch.
struct Pair {
  std::uint64_t a = 0;
  std::uint64_t pad[30] = {};
  std::uint64_t b = 0;
};

TEST(SeqLock, ConcurrentReadersNeverSeeATornValue) {
  SeqLock<Pair> s;
  std::atomic<bool> done{false};
  constexpr std::uint64_t kWrites = 50000;
  std::thread writer([&] {
    Pair p;
    for (std::uint64_t i = 1; i <= kWrites; ++i) {
      p.a = i;
      p.b = ~i;
      s.store(p);
    }
    done = true;
  });
  std::uint64_t torn = 0, reads = 0, lastSeen = 0, backwards = 0;
  auto reader = [&] {
    std::uint64_t localTorn = 0;
    while (!done.load()) {
      Pair p;
      s.load(p);
      if (p.b != ~p.a && !(p.a == 0 && p.b == 0)) ++localTorn;
    }
    return localTorn;
  };
  std::uint64_t otherTorn = 0;
  std::thread second([&] { otherTorn = reader(); });
  while (!done.load()) {
    Pair p;
    s.load(p);
    ++reads;
    if (p.b != ~p.a && !(p.a == 0 && p.b == 0)) ++torn;
    if (p.a < lastSeen) ++backwards;
    lastSeen = p.a;
  }
  writer.join();
  second.join();
  EXPECT_EQ(torn, 0u);
  EXPECT_EQ(otherTorn, 0u);
  EXPECT_EQ(backwards, 0u);  // one reader never sees time go backwards
  EXPECT_EQ(s.load().a, kWrites);
}

}  // namespace
}  // namespace xr::rt

// The impairment layer (transport/impairment.hpp): the shares of loss, duplication and reordering
// it was asked for, delays within latency +- jitter, release in due order, the same fate for the
// same seed, bad settings refused, a full queue dropping (counted) instead of growing, and no
// allocation once built.
#include "transport/impairment.hpp"

#include "support/alloc_counter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

namespace foresight::protocol {
namespace {

using Clock = ImpairedQueue::Clock;
using namespace std::chrono_literals;

struct Delivery {
  uint32_t id;
  double delay_ms;
};

// Pushes n datagrams 1 ms apart (each carrying its index), releasing as time goes on.
std::vector<Delivery> run(ImpairedQueue& q, int n) {
  std::vector<Delivery> out;
  const Clock::time_point t0{};
  Clock::time_point now = t0;
  auto take = [&](std::span<const uint8_t> d) {
    // Aligned as FlatBuffers reads a packet (UBSan caught misaligned slots once).
    EXPECT_EQ(reinterpret_cast<uintptr_t>(d.data()) % 8, 0u);
    uint32_t id;
    std::memcpy(&id, d.data(), sizeof id);
    out.push_back({id, std::chrono::duration<double, std::milli>(now - (t0 + std::chrono::milliseconds(id))).count()});
  };
  for (int i = 0; i < n + 2000; ++i, now += 1ms) {
    if (i < n) {
      uint8_t bytes[16] = {};
      const uint32_t id = static_cast<uint32_t>(i);
      std::memcpy(bytes, &id, sizeof id);
      q.push(bytes, now);
    }
    q.release(now, take);
  }
  return out;
}

TEST(Impairment, SharesAndDelaysAreWhatWasAskedFor) {
  ImpairmentConfig c;
  c.loss = 0.05, c.duplicate = 0.01, c.reorder = 0.01, c.latency_ms = 50, c.jitter_ms = 20, c.seed = 3;
  ImpairedQueue q(c, 0, 256);
  const int n = 20000;
  const auto got = run(q, n);
  const ImpairmentCounters& k = q.counters();
  EXPECT_EQ(k.pushed, static_cast<uint64_t>(n));
  EXPECT_NEAR(static_cast<double>(k.lost) / n, 0.05, 0.007);
  EXPECT_NEAR(static_cast<double>(k.duplicated) / n, 0.01, 0.003);
  EXPECT_EQ(k.overflowed, 0u);
  EXPECT_EQ(got.size(), k.pushed - k.lost + k.duplicated);
  EXPECT_EQ(q.in_flight(), 0u);
  int late = 0, overtaken = 0;
  for (size_t i = 0; i < got.size(); ++i) {
    EXPECT_GE(got[i].delay_ms, 30.0 - 1.0);  // 1 ms release granularity
    // latency + jitter, plus for a held-back one jitter + 20 ms more (1 ms release granularity).
    EXPECT_LE(got[i].delay_ms, 50 + 20 + 20 + 20 + 1.0);
    late += got[i].delay_ms > 71.0;
    if (i > 0 && got[i].id < got[i - 1].id) ++overtaken;
  }
  // Held back: about 1 % (the reorder share, a few of them within the jitter's reach); every
  // delivery out of order is counted once.
  EXPECT_NEAR(static_cast<double>(k.reordered) / n, 0.01, 0.003);
  EXPECT_GT(late, 0);
  EXPECT_GT(overtaken, n / 10) << "a 40 ms jitter window at 1 ms spacing reorders often";
}

TEST(Impairment, TheSameSeedGivesTheSameFateAndNoImpairmentIsTransparent) {
  ImpairmentConfig c;
  c.loss = 0.1, c.latency_ms = 10, c.jitter_ms = 5, c.seed = 9;
  ImpairedQueue a(c, 4), b(c, 4), other(c, 5);
  const auto x = run(a, 2000), y = run(b, 2000), z = run(other, 2000);
  ASSERT_EQ(x.size(), y.size());
  for (size_t i = 0; i < x.size(); ++i) EXPECT_EQ(x[i].id, y[i].id);
  EXPECT_NE(a.counters().lost, other.counters().lost) << "another salt, another fate";

  ImpairedQueue clear(ImpairmentConfig{}, 0);
  const auto all = run(clear, 500);
  ASSERT_EQ(all.size(), 500u);
  for (size_t i = 0; i < all.size(); ++i) {
    EXPECT_EQ(all[i].id, i);
    EXPECT_EQ(all[i].delay_ms, 0.0);
  }
}

TEST(Impairment, BadSettingsAreRefused) {
  std::string error;
  EXPECT_TRUE(impairment_valid({0.05, 0.01, 0.01, 50, 20, 1}, error));
  EXPECT_FALSE(impairment_valid({1.5, 0, 0, 0, 0, 1}, error));
  EXPECT_FALSE(impairment_valid({0, -0.1, 0, 0, 0, 1}, error));
  EXPECT_FALSE(impairment_valid({0, 0, NAN, 0, 0, 1}, error));
  EXPECT_FALSE(impairment_valid({0, 0, 0, -5, 0, 1}, error));
  EXPECT_FALSE(impairment_valid({0, 0, 0, 50, INFINITY, 1}, error));
  EXPECT_FALSE(error.empty());
}

TEST(Impairment, AFullQueueDropsAndCountsWithoutAllocating) {
  ImpairmentConfig c;
  c.latency_ms = 1000;
  ImpairedQueue q(c, 0, 8);
  uint8_t bytes[kMaxDatagramBytes] = {};
  foresight::test::AllocationCount count;
  for (int i = 0; i < 20; ++i) q.push(bytes, Clock::time_point{});
  q.push(std::span<const uint8_t>(bytes, sizeof bytes), Clock::time_point{});
  EXPECT_EQ(count.allocations(), 0);
  EXPECT_EQ(q.in_flight(), 8u);
  EXPECT_EQ(q.counters().overflowed, 13u);
  int released = 0;
  q.release(Clock::time_point{} + 2s, [&](std::span<const uint8_t>) { ++released; });
  EXPECT_EQ(released, 8);
}

}  // namespace
}  // namespace foresight::protocol

// any_discs_overlap (world/body_volume.hpp): the sweep along x finds exactly what comparing
// every pair finds, for crowds that touch and crowds that do not.
#include "world/body_volume.hpp"

#include "math/splitmix64.hpp"

#include <gtest/gtest.h>

#include <utility>
#include <vector>

namespace foresight {
namespace {

bool brute_force(const std::vector<BodyVolume>& b) {
  for (size_t i = 0; i < b.size(); ++i)
    for (size_t j = i + 1; j < b.size(); ++j) {
      const float r = b[i].radius_m + b[j].radius_m;
      const vec2 d = b[i].center_m - b[j].center_m;
      if (glm::dot(d, d) < r * r) return true;
    }
  return false;
}

TEST(DiscOverlap, TheSweepAgreesWithEveryPair) {
  SplitMix64 rng{3};
  int overlapping = 0;
  for (int trial = 0; trial < 400; ++trial) {
    // 2-300 bodies of 0.1-0.6 m on fields from crowded to sparse.
    const size_t n = 2 + rng.next() % 299;
    const float side = rng.uniform(2.0f, 400.0f);
    std::vector<BodyVolume> bodies(n);
    for (BodyVolume& b : bodies) {
      b.center_m = {rng.uniform(0.0f, side), rng.uniform(0.0f, side)};
      b.radius_m = rng.uniform(0.1f, 0.6f);
    }
    const bool expected = brute_force(bodies);
    overlapping += expected;
    EXPECT_EQ(any_discs_overlap(bodies), expected) << "trial " << trial;
  }
  EXPECT_GT(overlapping, 50);
  EXPECT_LT(overlapping, 350) << "both outcomes are exercised";
}

TEST(DiscOverlap, TouchingIsNotOverlappingAndOneWideBodyIsFound) {
  std::vector<BodyVolume> touching{{{0.0f, 0.0f}, 0.5f}, {{1.0f, 0.0f}, 0.5f}};
  EXPECT_FALSE(any_discs_overlap(touching));
  // A small body far along x from a wide one, overlapping it: the sweep's window is the widest radius.
  std::vector<BodyVolume> wide{{{0.0f, 0.0f}, 0.1f}, {{5.0f, 0.0f}, 0.1f}, {{9.5f, 0.0f}, 5.0f}};
  EXPECT_TRUE(any_discs_overlap(wide));
  std::vector<BodyVolume> none;
  EXPECT_FALSE(any_discs_overlap(none));
}

TEST(EnclosingVolume, HoldsBothDiscsAndBothHeights) {
  const BodyVolume a{vec2(0.0f, 0.0f), 0.3f, 0.0f, 1.7f};
  const BodyVolume b{vec2(0.5f, 0.2f), 0.2f, -0.01f, 1.8f};
  const BodyVolume inside{vec2(0.05f, 0.0f), 0.1f, 0.1f, 1.0f};
  for (const auto& [p, q] : {std::pair{a, b}, std::pair{b, a}}) {
    const BodyVolume e = enclosing_volume(p, q);
    for (const BodyVolume& v : {p, q}) EXPECT_LE(glm::length(v.center_m - e.center_m) + v.radius_m, e.radius_m + 1e-5f);
    // The smallest such disc: its diameter spans both discs along the line through their centres.
    EXPECT_NEAR(2.0f * e.radius_m, glm::length(b.center_m - a.center_m) + a.radius_m + b.radius_m, 1e-5f);
    EXPECT_FLOAT_EQ(e.y_min_m, -0.01f);
    EXPECT_FLOAT_EQ(e.y_max_m, 1.8f);
  }
  const BodyVolume e = enclosing_volume(inside, a);  // one inside the other: the outer one
  EXPECT_EQ(e.center_m, a.center_m);
  EXPECT_FLOAT_EQ(e.radius_m, a.radius_m);
}

}  // namespace
}  // namespace foresight

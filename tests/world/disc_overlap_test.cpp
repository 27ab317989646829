// any_discs_overlap (world/body_volume.hpp): the sweep along x finds exactly what comparing
// every pair finds, for crowds that touch and crowds that do not.
#include "world/body_volume.hpp"

#include "math/splitmix64.hpp"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace foresight

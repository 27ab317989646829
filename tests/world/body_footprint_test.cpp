// Body footprints (world/body_volume.hpp): the capsule fitted to a pose lies along its facing, holds
// every joint and is as narrow as the pose across its path; segment distances, the capsule-box
// test and the crowd sweep agree with plain reference computations.
#include "world/body_volume.hpp"

#include "math/splitmix64.hpp"
#include "world/collision_world.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <utility>
#include <vector>

namespace foresight {
namespace {

/// Distance from p to the volume's core segment, by sampling it finely (reference).
float sampled_core_distance(const BodyVolume& v, vec2 p) {
  float best = 1e9f;
  for (int i = 0; i <= 2000; ++i) {
    const float t = -1.0f + 2.0f * static_cast<float>(i) / 2000.0f;
    best = std::min(best, glm::length(v.center_m + t * v.half_axis_m - p));
  }
  return best;
}

BodyVolume random_capsule(SplitMix64& rng, float side) {
  BodyVolume b;
  b.center_m = {rng.uniform(0.0f, side), rng.uniform(0.0f, side)};
  b.radius_m = rng.uniform(0.1f, 0.4f);
  const float a = rng.uniform(-kPi, kPi);
  if (rng.uniform(0.0f, 1.0f) < 0.7f) b.half_axis_m = rng.uniform(0.0f, 0.5f) * vec2(std::cos(a), std::sin(a));
  return b;
}

TEST(BodyFootprint, PoseCapsuleLiesAlongTheFacingAndHoldsEveryJoint) {
  // A striding walker seen from above: feet 0.8 m apart front to back, shoulders 0.4 m across,
  // hands swinging, facing 30 degrees off +Z so the fit cannot rely on the axes.
  const float h = radians(30.0f);
  std::vector<vec3> joints;
  for (const vec2 p : {vec2(0.0f, 0.4f), vec2(0.05f, -0.4f), vec2(0.2f, 0.0f), vec2(-0.2f, 0.0f),
                       vec2(0.25f, 0.25f), vec2(-0.25f, -0.2f), vec2(0.0f, 0.05f)}) {
    const vec2 g = rotate_ground(p, h) + vec2(3.0f, -1.0f);
    joints.push_back({g.x, 1.0f, g.y});
  }
  joints[0].y = 0.05f;
  joints.back().y = 1.6f;
  const float margin = 0.08f;
  const vec2 facing(std::sin(h), std::cos(h));
  const BodyVolume v = body_volume_from_pose(joints, 2.0f * facing, margin, 0.12f);  // any length
  for (const vec3& j : joints) EXPECT_LE(sampled_core_distance(v, ground(j)), v.radius_m - margin + 1e-4f);
  EXPECT_FLOAT_EQ(v.y_min_m, 0.05f);
  EXPECT_FLOAT_EQ(v.y_max_m, 1.72f);
  // Across the path: the hands' 0.5 m plus the margin each side; along it: the stride.
  EXPECT_NEAR(2.0f * v.radius_m, 0.5f + 2.0f * margin, 1e-4f);
  EXPECT_NEAR(std::abs(glm::dot(glm::normalize(v.half_axis_m), facing)), 1.0f, 1e-5f);
  EXPECT_GT(glm::length(v.half_axis_m), 0.2f);
  // A disc around the same joints (the body of old) is as wide as the stride: about 1 m.
  EXPECT_LT(2.0f * v.radius_m, 0.7f);
}

TEST(BodyFootprint, CompactPoseIsADisc) {
  std::vector<vec3> joints;  // a ring of 0.2 m radius
  for (int i = 0; i < 12; ++i) {
    const float a = kTwoPi * static_cast<float>(i) / 12.0f;
    joints.push_back({0.2f * std::cos(a), 0.1f * static_cast<float>(i), 0.2f * std::sin(a)});
  }
  const BodyVolume v = body_volume_from_pose(joints, vec2(0.0f, 1.0f), 0.08f, 0.1f);
  for (const vec3& j : joints) EXPECT_LE(sampled_core_distance(v, ground(j)), v.radius_m - 0.08f + 1e-4f);
  EXPECT_LT(glm::length(v.half_axis_m), 1e-3f);
  EXPECT_NEAR(v.reach_m(), 0.28f, 1e-3f);
}

TEST(BodyFootprint, SegmentDistanceMatchesSampling) {
  SplitMix64 rng{9};
  for (int trial = 0; trial < 300; ++trial) {
    const BodyVolume a = random_capsule(rng, 1.5f), b = random_capsule(rng, 1.5f);
    float sampled = 1e9f;
    for (int i = 0; i <= 400; ++i) {
      const float t = -1.0f + 2.0f * static_cast<float>(i) / 400.0f;
      sampled = std::min(sampled, sampled_core_distance(b, a.center_m + t * a.half_axis_m));
    }
    const float d = std::sqrt(segment_distance_sq(a.center_m - a.half_axis_m, a.center_m + a.half_axis_m,
                                                  b.center_m - b.half_axis_m, b.center_m + b.half_axis_m));
    EXPECT_NEAR(d, sampled, 5e-3f) << "trial " << trial;
  }
}

TEST(BodyFootprint, CapsuleRectTestMatchesSampling) {
  SplitMix64 rng{17};
  int hits = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const BodyVolume v = random_capsule(rng, 3.0f);
    const vec2 lo(rng.uniform(0.5f, 2.0f), rng.uniform(0.5f, 2.0f));
    const vec2 hi = lo + vec2(rng.uniform(0.02f, 1.0f), rng.uniform(0.02f, 1.0f));
    float sampled = 1e9f;  // distance from the core to the rectangle, sampled along the core
    for (int i = 0; i <= 2000; ++i) {
      const vec2 p = v.center_m + (-1.0f + 2.0f * static_cast<float>(i) / 2000.0f) * v.half_axis_m;
      const float dx = std::max({lo.x - p.x, p.x - hi.x, 0.0f}), dz = std::max({lo.y - p.y, p.y - hi.y, 0.0f});
      sampled = std::min(sampled, std::sqrt(dx * dx + dz * dz));
    }
    if (std::abs(sampled - v.radius_m) < 2e-3f) continue;  // too close to call by sampling
    const bool expected = sampled < v.radius_m;
    hits += expected;
    EXPECT_EQ(capsule_overlaps_rect(v.center_m.x, v.center_m.y, v.half_axis_m.x, v.half_axis_m.y, v.radius_m,
                                    lo.x, lo.y, hi.x, hi.y),
              expected)
        << "trial " << trial;
  }
  EXPECT_GT(hits, 200);
  EXPECT_LT(hits, 1800);
}

bool brute_force(const std::vector<BodyVolume>& b) {
  for (size_t i = 0; i < b.size(); ++i)
    for (size_t j = i + 1; j < b.size(); ++j)
      if (footprints_overlap(b[i], b[j])) return true;
  return false;
}

TEST(BodyFootprint, CrowdSweepAgreesWithEveryPair) {
  SplitMix64 rng{3};
  int overlapping = 0;
  for (int trial = 0; trial < 400; ++trial) {
    // 2-300 bodies on fields from crowded to sparse.
    const size_t n = 2 + rng.next() % 299;
    const float side = rng.uniform(2.0f, 400.0f);
    std::vector<BodyVolume> bodies;
    for (size_t i = 0; i < n; ++i) bodies.push_back(random_capsule(rng, side));
    const bool expected = brute_force(bodies);
    overlapping += expected;
    EXPECT_EQ(any_footprints_overlap(bodies), expected) << "trial " << trial;
  }
  EXPECT_GT(overlapping, 50);
  EXPECT_LT(overlapping, 350) << "both outcomes are exercised";
}

TEST(BodyFootprint, TouchingIsNotOverlappingAndOneLongBodyIsFound) {
  std::vector<BodyVolume> touching{{{0.0f, 0.0f}, 0.5f}, {{1.0f, 0.0f}, 0.5f}};
  EXPECT_FALSE(any_footprints_overlap(touching));
  // A small body far along x from a long one, overlapping its far end: the sweep's window is the
  // longest reach.
  std::vector<BodyVolume> wide{{{0.0f, 0.0f}, 0.1f}, {{5.0f, 0.0f}, 0.1f}, {{9.5f, 0.0f}, 0.2f, 0.0f, 0.0f, {4.5f, 0.0f}}};
  EXPECT_TRUE(any_footprints_overlap(wide));
  // Side by side, parallel, 0.1 m apart: no contact though their reaches overlap.
  std::vector<BodyVolume> parallel{{{0.0f, 0.0f}, 0.2f, 0.0f, 0.0f, {0.0f, 0.5f}}, {{0.5f, 0.0f}, 0.2f, 0.0f, 0.0f, {0.0f, 0.5f}}};
  EXPECT_FALSE(any_footprints_overlap(parallel));
  std::vector<BodyVolume> none;
  EXPECT_FALSE(any_footprints_overlap(none));
}

}  // namespace
}  // namespace foresight

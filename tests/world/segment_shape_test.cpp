// Segment shapes: check orders are permutations, the sweep disc bounds every frame and the start.
#include "world_test_util.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

namespace foresight {
namespace {

std::vector<BodyVolume> numbered(int n) {
  std::vector<BodyVolume> v;
  for (int i = 0; i < n; ++i) v.push_back({{0.0f, 0.1f * i}, 0.3f, 0.0f, static_cast<float>(i)});
  return v;
}

std::vector<int> order_of(const SegmentCollisionShape& s) {
  std::vector<int> out;
  for (const BodyVolume& v : s.check_frames) out.push_back(static_cast<int>(v.y_max_m));
  return out;
}

TEST(SegmentShape, CheckOrders) {
  const auto frames = numbered(10);
  EXPECT_EQ(order_of(make_segment_shape(frames, FrameOrder::kSequential)),
            (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9}));
  EXPECT_EQ(order_of(make_segment_shape(frames, FrameOrder::kLastFirst)),
            (std::vector<int>{9, 0, 1, 2, 3, 4, 5, 6, 7, 8}));
  EXPECT_EQ(order_of(make_segment_shape(frames, FrameOrder::kCoarseToFine, 4)),
            (std::vector<int>{9, 5, 1, 0, 2, 3, 4, 6, 7, 8}));
  for (int n : {0, 1, 2, 31}) {
    for (FrameOrder o : {FrameOrder::kSequential, FrameOrder::kLastFirst, FrameOrder::kCoarseToFine}) {
      for (int stride : {0, 1, 3, 50}) {
        std::vector<int> got = order_of(make_segment_shape(numbered(n), o, stride));
        std::sort(got.begin(), got.end());
        std::vector<int> all(static_cast<std::size_t>(n));
        for (int i = 0; i < n; ++i) all[static_cast<std::size_t>(i)] = i;
        EXPECT_EQ(got, all) << "n " << n << " order " << static_cast<int>(o) << " stride " << stride;
      }
    }
  }
}

TEST(SegmentShape, SweepDiscBoundsFramesAndStart) {
  SyntheticSweepSpec spec;
  spec.forward_m = 2.0f;
  spec.turn_rad = 1.3f;
  spec.sideways_m = -0.4f;
  spec.half_length_m = 0.3f;
  const SegmentCollisionShape s = make_segment_shape(synthetic_sweep(spec));
  ASSERT_EQ(s.frames.size(), 30u);
  EXPECT_LE(glm::length(s.sweep_center_m), s.sweep_radius_m);
  for (const BodyVolume& v : s.frames)
    EXPECT_LE(glm::length(v.center_m - s.sweep_center_m) + v.reach_m(), s.sweep_radius_m + 1e-5f);
  EXPECT_FLOAT_EQ(s.max_reach_m, 0.65f);
  EXPECT_FLOAT_EQ(s.y_max_m, 1.85f);
  // Not absurdly loose: no more than the farthest frame's reach from the start plus a radius.
  EXPECT_LT(s.sweep_radius_m, 2.0f);
}

TEST(SegmentShape, SyntheticSweepGeometry) {
  const auto straight = synthetic_sweep(synthetic_walk());
  ASSERT_EQ(straight.size(), 30u);
  EXPECT_EQ(straight.front().center_m, vec2(0.0f));
  EXPECT_NEAR(straight.back().center_m.y, 1.2f, 1e-6f);
  EXPECT_FLOAT_EQ(synthetic_sweep(synthetic_crouch_walk()).back().y_max_m, 1.08f);
  SyntheticSweepSpec left;
  left.turn_rad = kPi / 2;
  const auto arc = synthetic_sweep(left);
  const float r = 1.2f / (kPi / 2);
  EXPECT_NEAR(arc.back().center_m.x, r, 1e-5f);  // Turning toward +X (the left).
  EXPECT_NEAR(arc.back().center_m.y, r, 1e-5f);
}

TEST(SegmentShape, BadFramesAreSanitised) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::vector<BodyVolume> frames = numbered(3);
  frames[1].radius_m = -1.0f;
  frames[2].y_min_m = 5.0f;  // Above y_max (2).
  SegmentCollisionShape s = make_segment_shape(frames);
  EXPECT_EQ(s.frames[1].radius_m, 0.0f);
  EXPECT_EQ(s.frames[2].y_min_m, 2.0f);
  EXPECT_EQ(s.frames[2].y_max_m, 5.0f);
  frames[0].center_m.x = nan;
  s = make_segment_shape(frames);
  EXPECT_TRUE(std::isnan(s.sweep_radius_m));
  // A frame with NaN always collides, even in an empty scene.
  Scene scene;
  scene.name = "empty";
  scene.bounds = {{-10, -10}, {10, 10}};
  const CollisionWorld world = test::build_world(scene);
  EXPECT_FALSE(segment_feasible(world, s, {}));
  EXPECT_TRUE(segment_feasible(world, make_segment_shape(numbered(3)), {}));
  EXPECT_TRUE(segment_feasible(world, make_segment_shape({}), {}));
}

}  // namespace
}  // namespace foresight

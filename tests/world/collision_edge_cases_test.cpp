// Disc-vs-box edge cases of the collision model, on a tiny scene built in code.
#include "world_test_util.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace foresight {
namespace {

/// One box [0, 1] x [0.5, 2] x [0, 1] (x, y, z) in bounds [-5, 5]^2.
Scene one_box_scene() {
  Scene s;
  s.name = "one-box";
  s.bounds = {{-5, -5}, {5, 5}};
  s.boxes.push_back({"b", BoxKind::kObstacle, {0, 0.5f, 0}, {1, 2, 1}});
  s.spawns.push_back({"s", {-4, -4}, 0});
  return s;
}

BodyVolume vol(float x, float z, float r, float y0 = 0.0f, float y1 = 1.85f) {
  return {{x, z}, r, y0, y1};
}

TEST(CollisionEdgeCases, PrimitiveDiscRect) {
  EXPECT_TRUE(disc_overlaps_rect(0.5f, 0.5f, 0.1f, 0, 0, 1, 1));   // Inside.
  EXPECT_TRUE(disc_overlaps_rect(0.5f, 0.5f, 0.0f, 0, 0, 1, 1));   // Inside, zero radius.
  EXPECT_TRUE(disc_overlaps_rect(1.0f, 0.5f, 0.0f, 0, 0, 1, 1));   // On the edge, zero radius.
  EXPECT_FALSE(disc_overlaps_rect(1.5f, 0.5f, 0.5f, 0, 0, 1, 1));  // Touching a side.
  EXPECT_TRUE(disc_overlaps_rect(1.5f, 0.5f, 0.5001f, 0, 0, 1, 1));
  // Touching a corner exactly: (0.75, 1.0) from the corner, radius 1.25 (exact in binary).
  EXPECT_FALSE(disc_overlaps_rect(1.75f, 2.0f, 1.25f, 0, 0, 1, 1));
  EXPECT_TRUE(disc_overlaps_rect(1.75f, 2.0f, 1.2501f, 0, 0, 1, 1));
  // Beside a corner diagonally but within the axis-aligned reach: not a hit (true distance).
  EXPECT_FALSE(disc_overlaps_rect(1.3f, 1.3f, 0.4f, 0, 0, 1, 1));
  EXPECT_TRUE(disc_overlaps_rect(1.3f, 1.3f, 0.43f, 0, 0, 1, 1));
  EXPECT_FALSE(y_ranges_overlap(0.0f, 0.5f, 0.5f, 2.0f));  // Head exactly at the box bottom.
  EXPECT_FALSE(y_ranges_overlap(2.0f, 3.0f, 0.5f, 2.0f));  // Feet exactly on the box top.
  EXPECT_TRUE(y_ranges_overlap(0.0f, 0.5001f, 0.5f, 2.0f));
}

TEST(CollisionEdgeCases, FrameAgainstOneBox) {
  const Scene scene = one_box_scene();
  const CollisionWorld world = test::build_world(scene);
  EXPECT_TRUE(frame_collides(world, vol(0.5f, 0.5f, 0.3f)));          // Inside.
  EXPECT_TRUE(frame_collides(world, vol(0.5f, 0.5f, 0.0f)));          // Inside, zero radius.
  EXPECT_FALSE(frame_collides(world, vol(1.5f, 0.5f, 0.5f)));         // Touching the side.
  EXPECT_TRUE(frame_collides(world, vol(1.5f, 0.5f, 0.51f)));
  EXPECT_FALSE(frame_collides(world, vol(1.75f, 2.0f, 1.25f)));       // Touching the corner.
  EXPECT_TRUE(frame_collides(world, vol(1.75f, 2.0f, 1.2501f)));
  EXPECT_FALSE(frame_collides(world, vol(0.5f, 0.5f, 0.3f, 0.0f, 0.5f)));  // Head at the bottom.
  EXPECT_TRUE(frame_collides(world, vol(0.5f, 0.5f, 0.3f, 0.0f, 0.51f)));
  EXPECT_FALSE(frame_collides(world, vol(0.5f, 0.5f, 0.3f, 2.0f, 3.0f)));  // Standing on top.
  EXPECT_TRUE(frame_collides(world, vol(0.5f, 0.5f, 0.3f, 1.99f, 3.0f)));
  // Larger than the fast radius: the neighbour-cell path.
  EXPECT_FALSE(frame_collides(world, vol(3.0f, 0.5f, 1.99f)));
  EXPECT_TRUE(frame_collides(world, vol(3.0f, 0.5f, 2.01f)));
  EXPECT_TRUE(frame_collides(world, vol(-4.0f, -4.0f, 6.0f)));
}

TEST(CollisionEdgeCases, BoundsAndBadInput) {
  const CollisionWorld world = test::build_world(one_box_scene());
  EXPECT_FALSE(frame_collides(world, vol(5.0f, 5.0f, 0.1f)));  // On the (closed) bounds edge.
  EXPECT_TRUE(frame_collides(world, vol(5.01f, 0.0f, 0.1f)));
  EXPECT_TRUE(frame_collides(world, vol(-3.0f, -5.01f, 0.1f)));
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  EXPECT_TRUE(frame_collides(world, vol(nan, 0.0f, 0.1f)));
  EXPECT_TRUE(frame_collides(world, vol(-3.0f, -3.0f, nan)));
  EXPECT_TRUE(frame_collides(world, vol(-3.0f, -3.0f, inf)));
  EXPECT_TRUE(frame_collides(CollisionWorld{}, vol(0, 0, 0.1f)));  // An unbuilt world blocks.
}

TEST(CollisionEdgeCases, BoxesOutsideTheBoundsStillCount) {
  Scene scene = one_box_scene();
  scene.boxes.push_back({"outside", BoxKind::kWall, {6, 0, -1}, {7, 2, 1}});
  const CollisionWorld world = test::build_world(scene);
  EXPECT_FALSE(frame_collides(world, vol(4.9f, 0.0f, 1.0f)));
  EXPECT_TRUE(frame_collides(world, vol(4.9f, 0.0f, 1.2f)));
  EXPECT_TRUE(frame_collides(world, vol(4.9f, 3.0f, 3.5f)));
}

TEST(CollisionEdgeCases, BuildRejectsBadBoundsAndAbsurdDensity) {
  Scene scene = one_box_scene();
  CollisionWorld world;
  std::string error;
  scene.bounds = {{0, 0}, {0, 10}};
  EXPECT_FALSE(collision_world_build(scene, world, error));
  EXPECT_NE(error.find("bounds"), std::string::npos) << error;
  // Many huge boxes each covering the whole grid: refused rather than allocating gigabytes.
  scene = one_box_scene();
  scene.bounds = {{0, 0}, {2000, 2000}};
  scene.boxes.assign(20, {"huge", BoxKind::kWall, {0, 0, 0}, {2000, 1, 2000}});
  CollisionWorldConfig config;
  config.cell_m = 0.5f;
  EXPECT_FALSE(collision_world_build(scene, world, error, config));
  EXPECT_NE(error.find("too dense"), std::string::npos) << error;
  EXPECT_TRUE(world.empty()) << "a failed build leaves the world alone";
}

}  // namespace
}  // namespace foresight

// Ground height queries: floor, height field (half-open cells, holes), steps (bridges too).
#include "world_test_util.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace foresight {
namespace {

/// Floor 0.1; a 2 x 2 field of 1 m cells at (0, 0) with one hole; a step over part of it.
Terrain small_terrain() {
  Terrain t;
  t.floor_y_m = 0.1f;
  t.height_field.origin_m = {0, 0};
  t.height_field.cell_m = 1.0f;
  t.height_field.count_x = 2;
  t.height_field.count_z = 2;
  t.height_field.heights_m = {0.2f, NAN, 0.4f, 0.5f};  // (0,0) (1,0) / (0,1) (1,1)
  t.steps.push_back({"bridge", {1.2f, -1.0f, 0.2f}, {1.5f, 0.3f, 0.5f}});
  return t;
}

float height(const Terrain& t, float x, float z) {
  float h = -99.0f;
  EXPECT_TRUE(terrain_height_at(t, {x, z}, h)) << x << ", " << z;
  return h;
}

bool ground(const Terrain& t, float x, float z) {
  float h = 0.0f;
  return terrain_height_at(t, {x, z}, h);
}

TEST(GroundTerrain, FloorFieldHolesAndSteps) {
  const Terrain t = small_terrain();
  EXPECT_FLOAT_EQ(height(t, -1.0f, 0.5f), 0.1f);   // Floor outside the field.
  EXPECT_FLOAT_EQ(height(t, 0.5f, 0.5f), 0.2f);
  EXPECT_FLOAT_EQ(height(t, 0.0f, 0.0f), 0.2f);    // Cells include their min edge...
  EXPECT_FLOAT_EQ(height(t, 0.5f, 1.0f), 0.4f);    // ...so z = 1 is row 1.
  EXPECT_FLOAT_EQ(height(t, 2.0f, 1.5f), 0.1f);    // ...and x = 2 is past the field: floor.
  EXPECT_FLOAT_EQ(height(t, 1.5f, 1.5f), 0.5f);
  EXPECT_FALSE(ground(t, 1.7f, 0.7f));             // The hole.
  EXPECT_FLOAT_EQ(height(t, 1.3f, 0.3f), 0.3f);    // A step bridging the hole.
  EXPECT_FLOAT_EQ(height(t, 1.5f, 0.5f), 0.3f);    // Step rectangles are closed.
  EXPECT_FALSE(ground(t, 1.51f, 0.5f));
  ground(t, NAN, 0.5f);                           // NaN never crashes.
}

TEST(GroundTerrain, StepsRaiseButNeverLower) {
  Terrain t = small_terrain();
  t.steps.push_back({"low", {-3, -1, -3}, {-2, 0.0f, -2}});  // Top below the floor.
  t.steps.push_back({"high", {-3, 0, -3}, {-2.5f, 0.7f, -2.5f}});
  EXPECT_FLOAT_EQ(height(t, -2.2f, -2.2f), 0.1f);
  EXPECT_FLOAT_EQ(height(t, -2.7f, -2.7f), 0.7f);
}

TEST(GroundTerrain, WorldQueryHonoursBoundsAndMatches) {
  Scene s;
  s.name = "g";
  s.bounds = {{-4, -4}, {4, 4}};
  s.terrain = small_terrain();
  const CollisionWorld world = test::build_world(s);
  float h = 0.0f;
  EXPECT_FALSE(ground_height_at(world, {4.1f, 0.0f}, h));
  EXPECT_TRUE(ground_height_at(world, {4.0f, 4.0f}, h));
  EXPECT_FLOAT_EQ(h, 0.1f);
  EXPECT_FALSE(ground_height_at(world, {1.7f, 0.7f}, h));
  EXPECT_TRUE(ground_height_at(world, {1.3f, 0.3f}, h));
  EXPECT_FLOAT_EQ(h, 0.3f);
}

TEST(GroundTerrain, TerrainRuleUsesTheStartHeight) {
  Scene s;
  s.name = "g";
  s.bounds = {{-4, -4}, {4, 4}};
  s.terrain = small_terrain();
  s.terrain.height_field.heights_m[1] = 0.9f;  // No hole: a 0.9 m block of ground instead.
  const CollisionWorld world = test::build_world(s);
  const BodyVolume v{{0.5f, 0.5f}, 0.1f, 0.2f, 1.9f};
  EXPECT_FALSE(frame_collides(world, v, 0.2f));
  EXPECT_FALSE(frame_collides(world, v, 0.2f + 0.25f));   // Exactly at the tolerance.
  EXPECT_TRUE(frame_collides(world, v, 0.2f + 0.26f));
  EXPECT_TRUE(frame_collides(world, v, 0.2f - 0.26f));
  const BodyVolume on_block{{1.5f, 0.5f}, 0.1f, 0.2f, 1.9f};
  EXPECT_TRUE(frame_collides(world, on_block, 0.2f));
  EXPECT_FALSE(frame_collides(world, on_block, 0.9f));
}

}  // namespace
}  // namespace foresight

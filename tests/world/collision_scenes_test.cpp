// Known-colliding and known-free placements of synthetic walking and crouching sweeps in each
// built-in scene (coordinates from data/scenes/generate_scenes.py; docs/SCENES.md has the maps).
#include "world_test_util.hpp"

#include <gtest/gtest.h>

namespace foresight {
namespace {

using test::placement_deg;

class SceneCollision : public ::testing::Test {
 protected:
  void use(const std::string& name) {
    scene_ = test::load_builtin_scene(name);
    world_ = test::build_world(scene_);
  }
  /// Checks segment_feasible, and that it agrees with the brute-force reference.
  bool feasible(const SegmentCollisionShape& shape, const Placement& p) {
    const bool fast = segment_feasible(world_, shape, p);
    const int brute = test::brute_first_collision(scene_, shape.frames, p,
                                                  world_.config.ground_tolerance_m);
    EXPECT_EQ(fast, brute < 0) << "grid and brute force disagree";
    EXPECT_EQ(segment_first_collision(world_, shape, p), brute);
    return fast;
  }

  Scene scene_;
  CollisionWorld world_;
  SegmentCollisionShape walk_ = make_segment_shape(synthetic_sweep(synthetic_walk()));
  SegmentCollisionShape crouch_ = make_segment_shape(synthetic_sweep(synthetic_crouch_walk()));
};

TEST_F(SceneCollision, Maze) {
  use("maze");
  // Start cell (1.25, 1.25): the corridor runs east (+X); walls north, south and west.
  EXPECT_TRUE(feasible(walk_, placement_deg(1.25f, 1.25f, 90)));    // Along the corridor.
  EXPECT_FALSE(feasible(walk_, placement_deg(1.25f, 1.25f, 0)));    // Into the south wall.
  EXPECT_FALSE(feasible(walk_, placement_deg(1.25f, 1.25f, -90)));  // Into the west wall.
  EXPECT_FALSE(feasible(walk_, placement_deg(1.25f, 1.25f, 180)));  // Into the north wall.
  // The corridor ends at the wall at x = 7.5: walking from 6.25 hits it, from 5.0 does not.
  EXPECT_FALSE(feasible(walk_, placement_deg(6.25f, 1.25f, 90)));
  EXPECT_TRUE(feasible(walk_, placement_deg(5.0f, 1.25f, 90)));
  // Turning into the side corridor at column 2 (x = 6.25 going south).
  EXPECT_TRUE(feasible(walk_, placement_deg(6.25f, 1.25f, 0)));
  // The long bottom corridor (row 7).
  EXPECT_TRUE(feasible(walk_, placement_deg(3.75f, 18.75f, 90)));
  EXPECT_FALSE(feasible(walk_, placement_deg(3.75f, 18.75f, 0)));  // Outer wall.
  // Crouching does not get through walls.
  EXPECT_FALSE(feasible(crouch_, placement_deg(1.25f, 1.25f, 0)));
  // A walk hugging the wall: 0.35 m radius at 0.36 m from the wall face is free, 0.34 is not.
  EXPECT_TRUE(feasible(walk_, placement_deg(1.25f, 0.2f + 0.36f, 90)));
  EXPECT_FALSE(feasible(walk_, placement_deg(1.25f, 0.2f + 0.34f, 90)));
}

TEST_F(SceneCollision, ObstaclesCrouchUnderBeamAndTable) {
  use("obstacles");
  // The beam across the first corridor at x = 5, bottom 1.25 m.
  EXPECT_FALSE(feasible(walk_, placement_deg(4.0f, 1.25f, 90)));
  EXPECT_TRUE(feasible(crouch_, placement_deg(4.0f, 1.25f, 90)));
  EXPECT_TRUE(feasible(walk_, placement_deg(2.5f, 1.25f, 90)));  // Stops short of it.
  // The table in the south corridor (row 6, z = 16.25), x 9.4..10.6, bottom 1.2 m.
  EXPECT_FALSE(feasible(walk_, placement_deg(9.4f, 16.25f, 90)));
  EXPECT_TRUE(feasible(crouch_, placement_deg(9.4f, 16.25f, 90)));
  EXPECT_TRUE(feasible(crouch_, placement_deg(9.8f, 16.25f, 90)));  // Starting under it.
  EXPECT_TRUE(feasible(walk_, placement_deg(7.5f, 16.25f, 90)));
  // The 0.3 m gaps beside the table are too narrow for a walking body.
  EXPECT_FALSE(feasible(walk_, placement_deg(9.4f, 15.35f, 90)));
}

TEST_F(SceneCollision, ObstaclesTurnAroundTheLowBarrier) {
  use("obstacles");
  // The barrier at x = 12.5 spans z 10.2..13.6 at 0.6-1.0 m: too low to crouch under.
  EXPECT_FALSE(feasible(walk_, placement_deg(11.5f, 12.0f, 90)));
  EXPECT_FALSE(feasible(crouch_, placement_deg(11.5f, 12.0f, 90)));
  // Around its open end (z 13.6..14.8).
  EXPECT_TRUE(feasible(walk_, placement_deg(11.5f, 14.2f, 90)));
  // Walking straight east at z = 13.3 clips the barrier's end; starting south (+Z) and turning
  // 90 degrees left (toward +X) curves around it instead.
  EXPECT_FALSE(feasible(walk_, placement_deg(11.5f, 13.3f, 90)));
  SyntheticSweepSpec turn = synthetic_walk();
  turn.forward_m = 1.5f;
  turn.turn_rad = radians(90.0f);
  EXPECT_TRUE(feasible(make_segment_shape(synthetic_sweep(turn)), placement_deg(11.5f, 13.3f, 0)));
}

TEST_F(SceneCollision, TerrainGapStepsSlopes) {
  use("terrain");
  // Level ground (x < 4 in the height field).
  EXPECT_TRUE(feasible(walk_, placement_deg(1.0f, 3.0f, 90)));
  // A flat walk over the 0.5 m gap at x 13.8..14.3: infeasible (the terrain planner strides it).
  EXPECT_FALSE(feasible(walk_, placement_deg(13.2f, 5.0f, 90)));
  EXPECT_FALSE(feasible(crouch_, placement_deg(13.2f, 5.0f, 90)));
  EXPECT_TRUE(feasible(walk_, placement_deg(12.2f, 5.0f, 90)));  // Stops before it.
  // Gentle slopes pass; the steep flank of the hill does not.
  EXPECT_TRUE(feasible(walk_, placement_deg(5.0f, 5.0f, 90)));
  EXPECT_FALSE(feasible(walk_, placement_deg(15.0f, 5.0f, 90)));
  // A 0.18 m step up is within tolerance; 0.36 m (two steps at once) is not.
  EXPECT_TRUE(feasible(walk_, placement_deg(1.2f, 15.0f, 90)));
  EXPECT_FALSE(feasible(walk_, placement_deg(1.9f, 15.0f, 90)));
  EXPECT_TRUE(feasible(walk_, placement_deg(2.4f, 15.0f, 90)));  // From the first step.
  // Along the upper step, and from it back down 0.18 m onto the lower one.
  EXPECT_TRUE(feasible(walk_, placement_deg(3.5f, 14.0f, 0)));
  EXPECT_TRUE(feasible(walk_, placement_deg(3.5f, 15.8f, 0)));
}

TEST_F(SceneCollision, TerrainLowDoorwayAndShelf) {
  use("terrain");
  // The doorway in the divider at x = 13.8..14.2, opening z 14.4..15.6, lintel from 1.4 m.
  EXPECT_FALSE(feasible(walk_, placement_deg(13.0f, 15.0f, 90)));
  EXPECT_TRUE(feasible(crouch_, placement_deg(13.0f, 15.0f, 90)));
  EXPECT_FALSE(feasible(crouch_, placement_deg(13.0f, 13.0f, 90)));  // The wall beside it.
  // The shelf along the north wall (z 19.1..19.7, y 1.1..1.3).
  EXPECT_FALSE(feasible(walk_, placement_deg(16.0f, 19.0f, 90)));
  EXPECT_TRUE(feasible(crouch_, placement_deg(16.0f, 19.0f, 90)));
  EXPECT_TRUE(feasible(walk_, placement_deg(16.0f, 18.6f, 90)));
}

TEST_F(SceneCollision, ArenaOpenFloorWallsAndPillars) {
  use("arena");
  CheckStats stats;
  EXPECT_TRUE(segment_feasible(world_, walk_, placement_deg(0.0f, 0.0f, 45), &stats));
  EXPECT_EQ(stats.sweep_early_outs, 1u) << "open floor is decided by the sweep test alone";
  EXPECT_EQ(stats.frame_checks, 0u);
  EXPECT_TRUE(feasible(walk_, placement_deg(0.0f, 0.0f, 45)));
  EXPECT_FALSE(feasible(walk_, placement_deg(7.0f, 0.0f, 90)));     // Low wall.
  EXPECT_FALSE(feasible(crouch_, placement_deg(7.0f, 0.0f, 90)));
  EXPECT_FALSE(feasible(walk_, placement_deg(-5.5f, -4.0f, 90)));   // Pillar.
  EXPECT_TRUE(feasible(walk_, placement_deg(-5.5f, -5.0f, 90)));
}

TEST_F(SceneCollision, StatsCountRealFrameChecks) {
  use("maze");
  CheckStats stats;
  // Into the wall: the check order visits the last frame first, which collides.
  EXPECT_FALSE(segment_feasible(world_, walk_, placement_deg(1.25f, 1.25f, 0), &stats));
  EXPECT_EQ(stats.clip_checks, 1u);
  EXPECT_EQ(stats.frame_checks, 1u);
  EXPECT_EQ(stats.feasible_clips, 0u);
  // A free corridor walk in the narrow maze: every frame is checked.
  EXPECT_TRUE(segment_feasible(world_, walk_, placement_deg(1.25f, 1.25f, 90), &stats));
  EXPECT_EQ(stats.clip_checks, 2u);
  EXPECT_EQ(stats.frame_checks, 1u + walk_.frames.size());
  EXPECT_EQ(stats.feasible_clips, 1u);
  EXPECT_EQ(stats.sweep_early_outs, 0u);
}

}  // namespace
}  // namespace foresight

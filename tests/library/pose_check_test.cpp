// The shown-pose check against the scene, and its tolerance for observers of quantised snapshots.
#include "library/library_source.hpp"
#include "library/pose_check.hpp"
#include "world/data_paths.hpp"

#include <gtest/gtest.h>

namespace foresight {
namespace {

TEST(PoseCheck, AToleranceForgivesAGrazeButNotAnOverlap) {
  const MotionLibrary lib = motion_library_default();
  Scene scene;
  CollisionWorld world;
  std::string error;
  ASSERT_TRUE(scene_world_load("arena", scene, world, error)) << error;
  const int idle = lib.graph.find_segment("idle");
  ASSERT_GE(idle, 0);
  // The arena's west wall is x in [-8.3, -8.0] (1 m high). Place the idle body so that its disc
  // reaches `depth` metres into the wall.
  const BodyVolume v = lib.volumes(idle)[0];
  auto at_depth = [&](float depth) {
    const float x = -8.0f + v.radius_m - depth - v.center_m.x;
    return PlaybackState{idle, 0, Placement{vec2(x, 0.0f), 0.0f}, -1};
  };
  PoseCheckScratch scratch;
  EXPECT_FALSE(shown_pose_collides(lib, world, at_depth(-0.01f), scratch)) << "1 cm clear";
  EXPECT_TRUE(shown_pose_collides(lib, world, at_depth(0.005f), scratch)) << "5 mm in";
  EXPECT_FALSE(shown_pose_collides(lib, world, at_depth(0.005f), scratch, 0.01f)) << "5 mm in, 1 cm tolerance";
  EXPECT_TRUE(shown_pose_collides(lib, world, at_depth(0.02f), scratch, 0.01f)) << "2 cm in, 1 cm tolerance";
}

}  // namespace
}  // namespace foresight

#include "graph_build/graph_edit.hpp"
#include "library_build/library_source.hpp"
#include "library_checks.hpp"
#include "world/collision_check.hpp"
#include "world/collision_world.hpp"
#include "world/data_paths.hpp"
#include "world/scene_load.hpp"

#include <gtest/gtest.h>

namespace foresight {
namespace {

const MotionLibrary& default_library() {
  static const MotionLibrary lib = motion_library_default();
  return lib;
}

// The straight (non-turning) locomotion segment with `required` tags, none of `excluded`, that
// moves furthest forward.
int straight_segment(const MotionLibrary& lib, uint32_t required, uint32_t excluded) {
  int best = -1;
  for (int s = 0; s < lib.graph.num_segments(); ++s) {
    const uint32_t tags = lib.graph.segments[s].tags;
    const Placement& end = lib.segment_motion[s].end;
    if ((tags & required) != required || (tags & excluded) || std::abs(end.heading_rad) > 0.1f)
      continue;
    if (best < 0 || end.pos_m.y > lib.segment_motion[best].end.pos_m.y) best = s;
  }
  return best;
}

TEST(DefaultLibrary, IsDeterministicAndStronglyConnected) {
  const MotionLibrary& lib = default_library();
  EXPECT_EQ(motion_library_default().content_hash, lib.content_hash);
  EXPECT_GE(lib.num_joints(), 20);
  EXPECT_EQ(largest_strongly_connected_component(lib.graph).size(),
            static_cast<size_t>(lib.graph.num_segments()));
  std::printf("[          ] default library: %zu clips, %d segments, %zu transitions, hash %016llx\n",
              lib.clips.size(), lib.graph.num_segments(), lib.graph.transitions.size(),
              static_cast<unsigned long long>(lib.content_hash));
}

TEST(DefaultLibrary, PlaybackThroughEveryEdgeIsContinuous) {
  // Authored boundary poses match, so an edge may not jump more than the fastest joint moves
  // in one frame next to it (times 1.5) plus 5 mm.
  test::expect_continuous_edges(default_library(), 1.5f, 0.005f);
}

TEST(DefaultLibrary, CrouchWalkPassesUnderTheBeamWhereWalkingHitsIt) {
  const MotionLibrary& lib = default_library();
  Scene scene;
  CollisionWorld world;
  std::string error;
  ASSERT_TRUE(scene_world_load("obstacles", scene, world, error)) << error;
  const int crouch = straight_segment(lib, kTagCrouch | kTagLocomotion, kTagTurn);
  const int walk = straight_segment(lib, kTagLocomotion, kTagCrouch | kTagTurn | kTagRun | kTagIdle);
  ASSERT_GE(crouch, 0);
  ASSERT_GE(walk, 0);
  // The beam spans the first corridor at x 4.85-5.15 (bottom 1.25 m); both segments start so
  // that their sweep crosses x = 5, walking along +X down the corridor's middle (z = 1.25). Each is
  // one step (a crouched step is 0.4 m), longer than the beam is thick.
  for (int s : {crouch, walk}) {
    const float forward = lib.segment_motion[s].end.pos_m.y;
    ASSERT_GT(forward, 0.35f) << lib.graph.segments[s].name;
    const Placement start{vec2(5.0f - 0.5f * forward, 1.25f), kPi / 2};
    const bool feasible = segment_feasible(world, lib.segment_shapes[s], start);
    EXPECT_EQ(feasible, s == crouch) << lib.graph.segments[s].name;
    // Away from the beam both are free: the difference is the beam, not the corridor.
    EXPECT_TRUE(segment_feasible(world, lib.segment_shapes[s], Placement{vec2(2.0f, 1.25f), kPi / 2}))
        << lib.graph.segments[s].name;
  }
}

TEST(DefaultLibrary, WalkingIntoAMazeWallIsInfeasible) {
  const MotionLibrary& lib = default_library();
  Scene scene;
  CollisionWorld world;
  std::string error;
  ASSERT_TRUE(scene_world_load("maze", scene, world, error)) << error;
  const int walk = straight_segment(lib, kTagLocomotion, kTagCrouch | kTagTurn | kTagRun | kTagIdle);
  ASSERT_GE(walk, 0);
  const SpawnPoint& spawn = scene.spawns.front();
  // From the spawn, facing the way the spawn faces, is free; facing the outer wall (-Z) is not.
  EXPECT_TRUE(segment_feasible(world, lib.segment_shapes[walk], {spawn.pos_m, spawn.heading_rad}));
  EXPECT_FALSE(segment_feasible(world, lib.segment_shapes[walk], {spawn.pos_m, kPi}));
}

}  // namespace
}  // namespace foresight

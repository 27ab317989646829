// The shown-pose check against the scene, and its tolerance for observers of quantised snapshots.
#include "library_build/library_source.hpp"
#include "anim/fk.hpp"
#include "library/playback.hpp"
#include "library/pose_check.hpp"
#include "world/body_volume.hpp"
#include "world/data_paths.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

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
  // The arena's west wall is x in [-8.3, -8.0] (1 m high). Place the idle body so that its flesh
  // (the westmost joint grown by the margin) reaches `depth` metres into the wall.
  Pose pose;
  playback_pose(lib, PlaybackState{idle, 0, Placement{}, -1}, pose);
  std::vector<vec3> joints(static_cast<size_t>(lib.num_joints()));
  std::vector<quat> rot(joints.size());
  fk_pose(lib.skeleton, pose.local_pos_m, pose.local_rot, joints, rot);
  float west = joints[0].x;
  for (const vec3& j : joints) west = std::min(west, j.x);
  auto at_depth = [&](float depth) {
    const float x = -8.0f + lib.body_margin_m - depth - west;
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

namespace foresight {
namespace {

// While a transition blends out, the pose shown differs from the clip's by up to the join's gap:
// the precomputed volumes the tree checks must hold those poses too, or a tree-approved motion
// can show a body a few millimetres inside a wall (it did: side steps entered from a turn on the
// spot, 2.6 mm).
TEST(PoseCheck, SegmentVolumesHoldEveryBlendedPoseShown) {
  const MotionLibrary lib = motion_library_default();
  const int n = lib.num_joints();
  Pose pose;
  std::vector<vec3> joints(static_cast<size_t>(n));
  std::vector<quat> rot(static_cast<size_t>(n));
  int checked = 0;
  for (size_t t = 0; t < lib.graph.transitions.size(); ++t) {
    const Transition& tr = lib.graph.transitions[t];
    const auto frames = lib.volumes(tr.to);
    for (int k = 0; k < tr.blend_frames && k < static_cast<int>(frames.size()); ++k) {
      playback_pose(lib, PlaybackState{tr.to, k, Placement{}, static_cast<int>(t)}, pose);
      fk_pose(lib.skeleton, pose.local_pos_m, pose.local_rot, joints, rot);
      const BodyVolume& kept = frames[static_cast<size_t>(k)];
      for (const vec3& j : joints) {  // every joint's flesh inside the kept capsule
        const float gap = std::sqrt(segment_distance_sq(ground(j), ground(j), kept.center_m - kept.half_axis_m,
                                                        kept.center_m + kept.half_axis_m));
        EXPECT_LE(gap + lib.body_margin_m, kept.radius_m + 1e-4f)
            << lib.graph.segments[tr.from].name << " -> " << lib.graph.segments[tr.to].name << " frame " << k;
      }
      for (const vec3& j : joints) EXPECT_LE(j.y + lib.head_top_margin_m, kept.y_max_m + 1e-4f);
      ++checked;
    }
  }
  EXPECT_GT(checked, 1000);
}

}  // namespace
}  // namespace foresight

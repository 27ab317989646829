// The steered terrain avatar (what the server runs for players on terrain): it walks where it is
// steered, turns smoothly (nothing already walked moves when it turns), strides over the terrain
// scene's gap, bends under its low doorway, stops on "stop", stands (and recovers) in front of a
// wall, keeps clear of other avatars, and shrugs off a NaN direction; without allocating.
#include "terrain/terrain_avatar.hpp"
#include "terrain_test_util.hpp"

#include "author/default_skeleton.hpp"
#include "anim/fk.hpp"
#include "support/alloc_counter.hpp"
#include "world/data_paths.hpp"
#include "world/scene_load.hpp"

#include <gtest/gtest.h>

#include <memory>

namespace foresight::terrain {
namespace {

const Scene& terrain_scene() {
  static const Scene scene = [] {
    Scene s;
    std::string error;
    EXPECT_TRUE(scene_load(scene_path("terrain"), s, error)) << error;
    return s;
  }();
  return scene;
}

using test::flat_scene;

vec2 dir_of(float heading) { return {std::sin(heading), std::cos(heading)}; }

struct Drive {
  std::vector<TerrainBodyPose> bodies;
  float max_pelvis_jump_m = 0.0f;  ///< Largest pelvis move between two frames.
  float max_heading_jump_rad = 0.0f;
  bool finite = true;
};

// Drives the avatar for `frames` frames toward `direction(frame)`.
template <class Direction>
Drive drive(TerrainAvatar& a, const Scene& scene, int frames, Direction direction,
          std::span<const TerrainNeighbour> others = {}) {
  Drive r;
  r.bodies.push_back(a.body);
  for (int f = 0; f < frames; ++f) {
    terrain_avatar_frame(a, scene, direction(f), others);
    const TerrainBodyPose& b = a.body;
    for (float v : terrain_body_angles(b)) r.finite = r.finite && std::isfinite(v);
    r.finite = r.finite && std::isfinite(b.pelvis_m.x) && std::isfinite(b.pelvis_m.y) && std::isfinite(b.pelvis_m.z);
    r.max_pelvis_jump_m = std::max(r.max_pelvis_jump_m, glm::length(b.pelvis_m - r.bodies.back().pelvis_m));
    r.max_heading_jump_rad =
        std::max(r.max_heading_jump_rad, std::abs(wrap_angle(b.heading_rad - r.bodies.back().heading_rad)));
    r.bodies.push_back(b);
  }
  return r;
}

std::unique_ptr<TerrainAvatar> make_avatar(const Scene& scene, vec2 at, float heading) {
  auto a = std::make_unique<TerrainAvatar>();
  EXPECT_TRUE(terrain_avatar_init(*a, TerrainAvatarConfig{}, scene, at, heading));
  return a;
}

TEST(TerrainAvatar, WalksWhereSteeredAndTurnsWithoutJumps) {
  const Scene scene = flat_scene();
  auto a = make_avatar(scene, {0.0f, 0.0f}, 0.0f);
  // 3 s ahead (+Z), then 6 s to the left (+X: heading +90 degrees): it turns walking, in steps.
  const Drive r = drive(*a, scene, 270, [](int f) { return f < 90 ? dir_of(0.0f) : dir_of(kPi / 2); });
  ASSERT_TRUE(r.finite);
  EXPECT_GT(a->steps, 12);
  EXPECT_EQ(a->refusals, 0);
  EXPECT_EQ(a->pivots, 0);
  EXPECT_GT(r.bodies[90].pelvis_m.z, 2.0f);  // 1.2 m/s for 3 s, less the first step's start
  EXPECT_NEAR(a->body.heading_rad, kPi / 2, 0.05f);
  EXPECT_GT(a->body.pelvis_m.x, 3.0f);
  // One frame is 1/30 s at about 1.2 m/s (the first step from standing lowers the pelvis fast):
  // the pelvis never jumps, the heading never snaps (it turns at most 0.5 rad over a step of
  // about 16 frames).
  EXPECT_LT(r.max_pelvis_jump_m, 0.1f);
  EXPECT_LT(r.max_heading_jump_rad, 0.1f);
}

TEST(TerrainAvatar, StopsAtTheEndOfTheStepOnStop) {
  const Scene scene = flat_scene();
  auto a = make_avatar(scene, {0.0f, 0.0f}, 0.0f);
  drive(*a, scene, 40, [](int) { return dir_of(0.0f); });
  const Drive r = drive(*a, scene, 60, [](int) { return vec2(0.0f); });
  // Within a step (at most about 0.75 s) it stands, and then stays exactly where it is.
  for (size_t f = 25; f < r.bodies.size(); ++f) EXPECT_EQ(r.bodies[f].pelvis_m, r.bodies.back().pelvis_m) << f;
  EXPECT_FALSE(a->stepping);
}

TEST(TerrainAvatar, StridesOverTheTerrainScenesGap) {
  // The gap runs across z = 5 at x 13.8-14.3 (terrain.json); walk east along z = 5.
  const Scene& scene = terrain_scene();
  auto a = make_avatar(scene, {12.0f, 5.0f}, kPi / 2);
  const Drive r = drive(*a, scene, 150, [](int) { return dir_of(kPi / 2); });
  ASSERT_TRUE(r.finite);
  EXPECT_GT(a->body.pelvis_m.x, 15.0f) << "stopped: " << terrain_step_status_name(a->last_status);
  EXPECT_LT(r.max_pelvis_jump_m, 0.1f);
}

TEST(TerrainAvatar, BendsUnderTheLowDoorwayOnTheSkeleton) {
  // The doorway's lintel: x 13.8-14.2, bottom 1.4 m, z 14.4-15.6; the avatar's head top stands
  // about 1.75 m up.
  const Scene& scene = terrain_scene();
  auto a = make_avatar(scene, {11.5f, 15.0f}, kPi / 2);
  const Skeleton skeleton = author::default_skeleton();
  TerrainSkeletonJoints joints;
  ASSERT_TRUE(terrain_skeleton_joints(skeleton, joints));
  Pose pose;
  std::vector<vec3> pos(static_cast<size_t>(skeleton.num_joints()));
  std::vector<quat> rot(pos.size());
  const int head = skeleton.find_joint("HeadTop_End");
  float lowest_head_under = 10.0f;
  int frames_under = 0;
  for (int f = 0; f < 200 && a->body.pelvis_m.x < 15.5f; ++f) {
    terrain_avatar_frame(*a, scene, dir_of(kPi / 2), {});
    terrain_body_to_pose(a->body, skeleton, joints, pose);
    fk_pose(skeleton, pose.local_pos_m, pose.local_rot, pos, rot);
    const vec3 top = pos[static_cast<size_t>(head)];
    if (top.x > 13.8f && top.x < 14.2f) {
      ++frames_under;
      lowest_head_under = std::min(lowest_head_under, top.y);
      EXPECT_LT(top.y, 1.4f) << "the head top is in the lintel at frame " << f;
    }
  }
  EXPECT_GT(a->body.pelvis_m.x, 15.5f) << "stopped: " << terrain_step_status_name(a->last_status);
  EXPECT_GT(frames_under, 0);
}

TEST(TerrainAvatar, StandsInFrontOfAWallAndWalksOnWhenSteeredAway) {
  const Scene scene = flat_scene({{"wall", BoxKind::kWall, vec3(-3.0f, 0.0f, 3.0f), vec3(3.0f, 2.5f, 3.3f)}});
  auto a = make_avatar(scene, {0.0f, 0.0f}, 0.0f);
  const Drive into = drive(*a, scene, 150, [](int) { return dir_of(0.0f); });
  ASSERT_TRUE(into.finite);
  EXPECT_GT(a->refusals, 0);
  EXPECT_EQ(a->last_status, TerrainStepStatus::kFootstepsFailed);
  for (const TerrainBodyPose& b : into.bodies) EXPECT_LT(b.pelvis_m.z, 3.0f - 0.1f);
  // Steered away (back the way it came) it turns on the spot and walks again.
  const float z = a->body.pelvis_m.z;
  const Drive back = drive(*a, scene, 150, [](int) { return dir_of(kPi); });
  EXPECT_EQ(a->pivots, 1);
  EXPECT_LT(a->body.pelvis_m.z, z - 1.0f);
  EXPECT_LT(back.max_pelvis_jump_m, 0.1f);
  EXPECT_LT(back.max_heading_jump_rad, 0.15f);  // 4 rad/s on the spot
}

TEST(TerrainAvatar, KeepsClearOfAnotherAvatar) {
  const Scene scene = flat_scene();
  auto a = make_avatar(scene, {0.0f, 0.0f}, 0.0f);
  const TerrainNeighbour other{{0.0f, 2.0f}, {0.0f, 2.0f}};
  drive(*a, scene, 150, [](int) { return dir_of(0.0f); }, std::span(&other, 1));
  EXPECT_TRUE(a->vetoed);
  // It stopped one step short (a step is at most 0.9 m).
  EXPECT_LT(glm::length(terrain_avatar_ground(*a) - other.now_m), TerrainAvatarConfig{}.personal_space_m + 0.9f);
  EXPECT_GE(glm::length(terrain_avatar_ground(*a) - other.now_m), TerrainAvatarConfig{}.personal_space_m);
}

TEST(TerrainAvatar, NonFiniteDirectionStands) {
  const Scene scene = flat_scene();
  auto a = make_avatar(scene, {0.0f, 0.0f}, 0.0f);
  const TerrainBodyPose before = a->body;
  for (int f = 0; f < 30; ++f) EXPECT_FALSE(terrain_avatar_frame(*a, scene, vec2(NAN, 1.0f), {}));
  EXPECT_EQ(a->body.pelvis_m, before.pelvis_m);
  EXPECT_EQ(a->steps, 0);
}

TEST(TerrainAvatar, NoGroundAtTheSpawnIsRefused) {
  const Scene scene = flat_scene();
  auto a = std::make_unique<TerrainAvatar>();
  EXPECT_FALSE(terrain_avatar_init(*a, TerrainAvatarConfig{}, scene, {50.0f, 0.0f}, 0.0f));
}

TEST(TerrainAvatar, WalksAndTurnsWithoutAllocating) {
  const Scene& scene = terrain_scene();
  auto a = make_avatar(scene, {2.0f, 6.0f}, kPi / 2);
  int planned = 0;
  {
    foresight::test::AllocationCount count;
    for (int f = 0; f < 240; ++f) planned += terrain_avatar_frame(*a, scene, dir_of(f < 120 ? kPi / 2 : 0.3f), {});
    EXPECT_EQ(count.allocations(), 0);
  }
  EXPECT_GT(planned, 10);
}

}  // namespace
}  // namespace foresight::terrain

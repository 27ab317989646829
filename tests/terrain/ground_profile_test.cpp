// Ground profiles: paths, synthetic profiles, and the terrain scene cut along walking paths.
#include "terrain_test_util.hpp"

#include "world/data_paths.hpp"
#include "world/scene_load.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace foresight::terrain {
namespace {

Scene load_terrain_scene() {
  Scene scene;
  std::string error;
  EXPECT_TRUE(scene_load(scene_path("terrain"), scene, error)) << error;
  return scene;
}

TEST(GroundProfile, PathsLinesAndArcs) {
  const GroundPath line{{1.0f, 2.0f}, radians(90.0f), 0.0f};  // Facing +X.
  const vec2 p = ground_path_point(line, 3.0f);
  EXPECT_NEAR(p.x, 4.0f, 1e-5f);
  EXPECT_NEAR(p.y, 2.0f, 1e-5f);
  // A quarter circle of radius 2 from heading 0 (+Z) turning toward +X.
  const GroundPath arc = ground_path_from_velocity({0.0f, 0.0f}, 0.0f, 1.0f, 0.5f);
  EXPECT_NEAR(arc.curvature_per_m, 0.5f, 1e-6f);
  const vec2 q = ground_path_point(arc, kPi);  // Arc length of a quarter of a 2 m circle.
  EXPECT_NEAR(q.x, 2.0f, 1e-4f);
  EXPECT_NEAR(q.y, 2.0f, 1e-4f);
  EXPECT_NEAR(ground_path_heading(arc, kPi), kPi / 2.0f, 1e-5f);
  // Standing still: a straight path, never NaN.
  const GroundPath still = ground_path_from_velocity({0.0f, 0.0f}, 0.0f, 0.0f, 1.0f);
  EXPECT_EQ(still.curvature_per_m, 0.0f);
}

TEST(GroundProfile, ASteeredPathKeepsTheWalkedStretchAndThenTurns) {
  // Twice steered, as the terrain avatar does at each step: the stretch from the rear to the
  // stance foot lies exactly where it lay on the walked path, then the path turns by the asked
  // angle over the asked length and runs straight.
  const GroundPath first = ground_path_from_velocity({1.0f, 2.0f}, 0.3f, 1.2f, 0.5f);
  const GroundPath second = ground_path_steer(first, 0.4f, 1.0f, 0.3f, 0.4f, 0.65f);
  const GroundPath third = ground_path_steer(second, 0.3f + 0.6f - 0.55f, 0.3f + 0.6f, 0.3f, -0.5f, 0.65f);
  for (float x = 0.0f; x <= 0.6f; x += 0.05f) {
    EXPECT_LT(glm::length(ground_path_point(second, 0.3f + x) - ground_path_point(first, 0.4f + x)), 1e-5f) << x;
    EXPECT_NEAR(wrap_angle(ground_path_heading(second, 0.3f + x) - ground_path_heading(first, 0.4f + x)), 0.0f, 1e-5f);
  }
  const float stance2 = 0.3f + 0.6f;
  EXPECT_NEAR(wrap_angle(ground_path_heading(second, stance2 + 0.65f) - ground_path_heading(first, 1.0f)), 0.4f, 1e-5f);
  EXPECT_NEAR(wrap_angle(ground_path_heading(second, stance2 + 3.0f) - ground_path_heading(second, stance2 + 0.65f)), 0.0f,
              1e-5f) << "straight after the turn";
  // The third keeps the second's stretch, which itself partly lies on the first.
  for (float x = 0.0f; x <= 0.55f; x += 0.05f)
    EXPECT_LT(glm::length(ground_path_point(third, 0.3f + x) - ground_path_point(second, stance2 - 0.55f + x)), 1e-5f) << x;
  EXPECT_LE(third.num_pieces, 4);
  // Behind the rear foot: a straight lead-in along the rear foot's heading.
  EXPECT_NEAR(wrap_angle(ground_path_heading(second, 0.0f) - ground_path_heading(first, 0.4f)), 0.0f, 1e-5f);
}

TEST(GroundProfile, SyntheticProfilesAndCapacity) {
  GroundProfile profile;
  ground_profile_flat(profile, 1.0f, 0.3f);
  EXPECT_EQ(profile.num_samples, 50);
  float h = 0.0f;
  EXPECT_TRUE(profile.height_at(0.5f, h));
  EXPECT_FLOAT_EQ(h, 0.3f);
  EXPECT_FALSE(profile.height_at(1.0f, h));
  EXPECT_FALSE(profile.height_at(-0.01f, h));
  ground_profile_fill(profile, 0.2f, 0.4f, NAN);
  EXPECT_FALSE(profile.height_at(0.3f, h));
  ground_profile_flat(profile, 1000.0f, 0.0f);
  EXPECT_EQ(profile.num_samples, kMaxProfileSamples);
  ground_profile_flat(profile, -1.0f, 0.0f);
  EXPECT_EQ(profile.num_samples, 0);
  GroundProfile a, b;
  ground_profile_random(a, 5, 14.0f);
  ground_profile_random(b, 5, 14.0f);
  for (int i = 0; i < a.num_samples; ++i) {
    const auto k = static_cast<std::size_t>(i);
    EXPECT_TRUE((std::isnan(a.height_m[k]) && std::isnan(b.height_m[k])) || a.height_m[k] == b.height_m[k]);
  }
}

TEST(GroundProfile, TerrainSceneProfilesLoad) {
  const Scene scene = load_terrain_scene();
  ASSERT_EQ(scene.name, "terrain");
  GroundProfile profile;
  // South half, east along z = 5: level, rolling slopes, the 0.5 m gap at x 13.8..14.3, the hill.
  ASSERT_TRUE(ground_profile_from_scene(scene, {{1.0f, 5.0f}, radians(90.0f), 0.0f}, 18.9f,
                                        ProfileCutOptions{}, profile));
  EXPECT_EQ(profile.num_samples, 945);
  float gap_from = -1.0f, gap_to = -1.0f, hill_top = 0.0f, slope_min = 1.0f, slope_max = -1.0f;
  for (int i = 0; i < profile.num_samples; ++i) {
    const float x = 1.0f + (static_cast<float>(i) + 0.5f) * profile.spacing_m;
    const float h = profile.height_m[static_cast<std::size_t>(i)];
    if (std::isnan(h)) {
      if (gap_from < 0.0f) gap_from = x;
      gap_to = x;
      continue;
    }
    if (x >= 4.0f && x < 12.0f) slope_min = std::min(slope_min, h), slope_max = std::max(slope_max, h);
    if (x > 14.3f && x < 19.6f) hill_top = std::max(hill_top, h);
  }
  EXPECT_NEAR(gap_from, 13.8f, 0.02f);
  EXPECT_NEAR(gap_to, 14.3f, 0.02f);
  EXPECT_LT(slope_min, -0.1f);
  EXPECT_GT(slope_max, 0.1f);
  EXPECT_GT(hill_top, 0.5f);
  // The east wall shows as a vertical wall at x 19.7.
  float wall = 0.0f;
  EXPECT_TRUE(profile.height_at(18.8f, wall));
  EXPECT_FLOAT_EQ(wall, 2.5f);

  // North half along z = 15: step-low (0.18) then step-high on it (0.36), and through the low
  // doorway (the lintel is the upper body's business, not the legs').
  ASSERT_TRUE(ground_profile_from_scene(scene, {{1.0f, 15.0f}, radians(90.0f), 0.0f}, 15.0f,
                                        ProfileCutOptions{}, profile));
  float h = 0.0f;
  ASSERT_TRUE(profile.height_at(1.5f, h));  // x = 2.5
  EXPECT_FLOAT_EQ(h, 0.18f);
  ASSERT_TRUE(profile.height_at(3.0f, h));  // x = 4.0
  EXPECT_FLOAT_EQ(h, 0.36f);
  ASSERT_TRUE(profile.height_at(13.0f, h));  // x = 14.0, in the doorway
  EXPECT_FLOAT_EQ(h, 0.0f);
  // Outside the bounds there is no ground.
  ASSERT_TRUE(ground_profile_from_scene(scene, {{19.0f, 15.0f}, radians(90.0f), 0.0f}, 3.0f,
                                        ProfileCutOptions{}, profile));
  EXPECT_FALSE(profile.height_at(2.5f, h));
}

TEST(GroundProfile, PlannerCrossesTheTerrainScenesGapAndClimbsTheSteps) {
  const Scene scene = load_terrain_scene();
  FootstepPlanner planner;
  ASSERT_TRUE(footstep_planner_init(planner, FootstepPlannerConfig{}));
  GroundProfile profile;
  // East along z = 5 from x = 11: the level strip, then the gap.
  ASSERT_TRUE(ground_profile_from_scene(scene, {{11.0f, 5.0f}, radians(90.0f), 0.0f}, 8.0f,
                                        ProfileCutOptions{}, profile));
  auto log = test::walk_with_planner(planner, profile, 0.3f, 4.0f);
  EXPECT_EQ(log.last_status, FootstepStatus::kOk) << footstep_status_name(log.last_status);
  bool crossed = false;
  for (const WalkStep& s : log.steps) {
    crossed = crossed || (s.stance.x_m < 2.8f && s.land.x_m > 3.3f);
    EXPECT_FALSE(test::foot_in_gap(profile, planner.config.walk, s.land.x_m));
    EXPECT_LE(test::swing_penetration_m(profile, planner.config.walk, s), 0.005f);
  }
  EXPECT_TRUE(crossed);
  // East along z = 15 from x = 0.5: onto step-low, onto step-high, down twice.
  ASSERT_TRUE(ground_profile_from_scene(scene, {{0.5f, 15.0f}, radians(90.0f), 0.0f}, 11.0f,
                                        ProfileCutOptions{}, profile));
  log = test::walk_with_planner(planner, profile, 0.3f, 7.0f);
  EXPECT_EQ(log.last_status, FootstepStatus::kOk) << footstep_status_name(log.last_status);
  int up = 0, down = 0;
  for (const WalkStep& s : log.steps) {
    up += s.kind == StepKind::kUphill;
    down += s.kind == StepKind::kDownhill;
    EXPECT_LE(test::swing_penetration_m(profile, planner.config.walk, s), 0.005f);
  }
  EXPECT_EQ(up, 2);
  EXPECT_EQ(down, 2);
}

}  // namespace
}  // namespace foresight::terrain

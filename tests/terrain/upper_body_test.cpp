// The upper-body planner (paper 5): the patterns in the open, bending under the terrain scene's low
// doorway, lifting an arm past an object at arm height, a clear failure in front of a chest-high
// wall, bad input, determinism. The walker (terrain_walker.hpp) runs footsteps and upper body
// together, as the game does.
#include "terrain/terrain_walker.hpp"
#include "terrain_test_util.hpp"

#include "world/data_paths.hpp"
#include "world/scene_load.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

namespace foresight::terrain {
namespace {

using test::flat_scene;

SceneBox box(vec3 lo, vec3 hi) {
  SceneBox b;
  b.kind = BoxKind::kObstacle;
  b.min_m = lo;
  b.max_m = hi;
  return b;
}

/// Every committed frame of a walk: pelvis and upper body.
struct WalkRecord {
  std::vector<PelvisFrame> pelvis;
  std::vector<UpperBodyConfig> upper;
  TerrainStepStatus last = TerrainStepStatus::kOk;
  int steps = 0;
  int waist_backtracks = 0;  ///< Over every plan of the walk.
};

WalkRecord walk(TerrainWalker& walker, const Scene& scene, const GroundPath& path, float goal_m) {
  WalkRecord r;
  EXPECT_TRUE(terrain_walker_start(walker, scene, path, goal_m + 5.0f));
  while (terrain_walker_travelled_m(walker) < goal_m && r.steps < 60) {
    r.last = terrain_walker_step(walker, scene);
    r.waist_backtracks += walker.upper_plan.parts[static_cast<size_t>(BodyPart::kWaist)].backtracks;
    if (r.last != TerrainStepStatus::kOk) break;
    ++r.steps;
    for (int t = r.pelvis.empty() ? 0 : 1; t <= walker.step_frames; ++t) {
      r.pelvis.push_back(walker.track[static_cast<size_t>(t)]);
      r.upper.push_back(walker.upper_plan.frames[static_cast<size_t>(t)]);
    }
  }
  return r;
}

bool finite(const UpperBodyConfig& c) {
  for (const PartConfig* q : {&c.waist, &c.arms[0], &c.arms[1]})
    for (float v : *q)
      if (!std::isfinite(v)) return false;
  return true;
}

/// Re-checks a recorded walk's volumes against the scene's boxes: what the player would see.
int colliding_frames(const WalkRecord& r, const Scene& scene, const UpperBodyParams& body) {
  UpperBodyObstacles obstacles;
  gather_upper_body_obstacles(scene, r.pelvis, 2.0f, 0.5f, obstacles);
  int bad = 0;
  for (size_t t = 0; t < r.pelvis.size(); ++t) bad += upper_body_clear(body, r.pelvis[t], r.upper[t], obstacles) ? 0 : 1;
  return bad;
}

std::unique_ptr<TerrainWalker> make_walker(std::uint64_t growth_seed = UpperBodyPlannerConfig{}.seed) {
  auto w = std::make_unique<TerrainWalker>();
  TerrainWalkerConfig config;
  config.upper_body.seed = growth_seed;
  EXPECT_TRUE(terrain_walker_init(*w, config));
  return w;
}

TEST(UpperBody, InTheOpenTheWaistStaysErectAndTheArmsSwingAgainstTheLegs) {
  const Scene scene = flat_scene();
  auto walker = make_walker();
  const WalkRecord r = walk(*walker, scene, GroundPath{{0.0f, 0.0f}, 0.0f, 0.0f}, 5.0f);
  ASSERT_EQ(r.last, TerrainStepStatus::kOk);
  ASSERT_GE(r.steps, 6);
  const UpperBodyParams& body = walker->config.upper_body.body;
  int swings = 0;
  for (size_t t = 0; t < r.pelvis.size(); ++t) {
    ASSERT_TRUE(finite(r.upper[t]));
    EXPECT_EQ(r.upper[t].waist[0], 0.0f);
    EXPECT_EQ(r.upper[t].waist[1], 0.0f);
    for (BodyPart arm : {BodyPart::kLeftArm, BodyPart::kRightArm}) {
      const PartConfig pattern = upper_body_pattern(body, arm, r.pelvis[t]);
      for (int d = 0; d < kArmDof; ++d) EXPECT_NEAR(r.upper[t].part(arm)[d], pattern[d], 1e-5f) << t;
    }
    // Opposite the legs: the arm is forward when its own side's thigh is back, and the other way.
    const float left_hip = r.pelvis[t].left_hip_rad, left_arm = r.upper[t].arms[0][0];
    if (std::abs(left_hip) > 0.2f) {
      EXPECT_LT(left_hip * left_arm, 0.0f) << t;
      ++swings;
    }
  }
  EXPECT_GT(swings, 20);
  EXPECT_EQ(walker->upper_plan.parts[0].backtracks, 0);
}

TEST(UpperBody, BendsUnderTheLowDoorway) {
  Scene scene;
  std::string error;
  ASSERT_TRUE(scene_load(scene_path("terrain"), scene, error)) << error;
  const SceneBox* lintel = nullptr;
  for (const SceneBox& b : scene.boxes)
    if (b.name == "low-doorway") lintel = &b;
  ASSERT_NE(lintel, nullptr);
  auto walker = make_walker();
  // East along z = 15 through the opening (z 14.4..15.6 under the lintel at 1.4 m).
  const WalkRecord r = walk(*walker, scene, GroundPath{{11.0f, 15.0f}, kPi / 2, 0.0f}, 4.5f);
  ASSERT_EQ(r.last, TerrainStepStatus::kOk) << terrain_step_status_name(r.last) << " after " << r.steps << " steps";
  ASSERT_GT(r.pelvis.back().pos_m.x, lintel->max_m.x + 0.3f) << "did not get through";
  const UpperBodyParams& body = walker->config.upper_body.body;
  float max_flexion = 0.0f;
  int under = 0, erect_would_hit = 0;
  for (size_t t = 0; t < r.pelvis.size(); ++t) {
    max_flexion = std::max(max_flexion, r.upper[t].waist[0]);
    const vec3 top = head_top(body, r.pelvis[t], r.upper[t].waist);
    if (top.x >= lintel->min_m.x && top.x <= lintel->max_m.x) {
      ++under;
      EXPECT_LT(top.y, lintel->min_m.y) << "head in the lintel at frame " << t;
    }
    const vec3 erect = head_top(body, r.pelvis[t], PartConfig{});
    if (erect.x >= lintel->min_m.x - 0.1f && erect.x <= lintel->max_m.x + 0.1f && erect.y > lintel->min_m.y)
      ++erect_would_hit;
  }
  EXPECT_GT(max_flexion, 0.9f) << "the waist did not bend";
  // Foresight: the bend starts in time, no window walks into the lintel erect and backs out.
  EXPECT_EQ(r.waist_backtracks, 0);
  EXPECT_GT(under, 0);
  EXPECT_GT(erect_would_hit, 0) << "an erect actor would have passed: the test proves nothing";
  EXPECT_EQ(colliding_frames(r, scene, body), 0);
  // And erect again once through.
  EXPECT_LT(r.upper.back().waist[0], 0.2f);
}

// A counter on the actor's left (+x) at hand height: the hanging left hand would touch it. Every
// seed of the grown nodes gets past (the arm leaves its swing in time, it does not depend on luck).
class UpperBodyGrowthSeed : public ::testing::TestWithParam<std::uint64_t> {};

TEST_P(UpperBodyGrowthSeed, LiftsAnArmPastAnObjectAtArmHeight) {
  const Scene scene = flat_scene({box({0.21f, 0.55f, 2.0f}, {0.8f, 1.15f, 3.0f})});
  auto walker = make_walker(GetParam());
  const WalkRecord r = walk(*walker, scene, GroundPath{{0.0f, 0.0f}, 0.0f, 0.0f}, 4.5f);
  ASSERT_EQ(r.last, TerrainStepStatus::kOk) << terrain_step_status_name(r.last);
  const UpperBodyParams& body = walker->config.upper_body.body;
  UpperBodyObstacles obstacles;
  gather_upper_body_obstacles(scene, r.pelvis, 2.0f, 0.5f, obstacles);
  int pattern_hits = 0;
  float left_deviation = 0.0f, right_deviation = 0.0f;
  for (size_t t = 0; t < r.pelvis.size(); ++t) {
    BodySpheres s;
    arm_spheres(body, r.pelvis[t], r.upper[t].waist, BodyPart::kLeftArm,
                upper_body_pattern(body, BodyPart::kLeftArm, r.pelvis[t]), s);
    pattern_hits += spheres_clear(s, obstacles) ? 0 : 1;
    for (int arm = 0; arm < 2; ++arm) {
      const BodyPart part = arm == 0 ? BodyPart::kLeftArm : BodyPart::kRightArm;
      const PartConfig p = upper_body_pattern(body, part, r.pelvis[t]);
      float d = 0.0f;
      for (int k = 0; k < kArmDof; ++k) d = std::max(d, std::abs(r.upper[t].part(part)[k] - p[k]));
      (arm == 0 ? left_deviation : right_deviation) = std::max(arm == 0 ? left_deviation : right_deviation, d);
    }
  }
  EXPECT_GT(pattern_hits, 5) << "the swinging arm would not have touched the counter";
  EXPECT_EQ(colliding_frames(r, scene, body), 0);
  EXPECT_GT(left_deviation, 0.3f) << "the left arm kept its swing";
  EXPECT_LT(right_deviation, 1e-4f) << "the right arm had nothing to avoid";
}

INSTANTIATE_TEST_SUITE_P(Seeds, UpperBodyGrowthSeed, ::testing::Range<std::uint64_t>(1, 9));

TEST(UpperBody, TurnsTheWaistPastAnObjectAtShoulderHeight) {
  // A ledge on the actor's right (-x) at shoulder height, 4.5 cm from the right shoulder: no arm
  // motion moves a shoulder, so the waist turns (the paper's Fig. 9b).
  const Scene scene = flat_scene({box({-0.8f, 1.25f, 2.0f}, {-0.22f, 1.7f, 3.0f})});
  auto walker = make_walker();
  const WalkRecord r = walk(*walker, scene, GroundPath{{0.0f, 0.0f}, 0.0f, 0.0f}, 4.5f);
  ASSERT_EQ(r.last, TerrainStepStatus::kOk) << terrain_step_status_name(r.last);
  const UpperBodyParams& body = walker->config.upper_body.body;
  UpperBodyObstacles obstacles;
  gather_upper_body_obstacles(scene, r.pelvis, 2.0f, 0.5f, obstacles);
  int erect_hits = 0;
  float max_turn = 0.0f;
  for (size_t t = 0; t < r.pelvis.size(); ++t) {
    BodySpheres s;
    waist_spheres(body, r.pelvis[t], PartConfig{}, s);
    erect_hits += spheres_clear(s, obstacles) ? 0 : 1;
    max_turn = std::max(max_turn, std::abs(r.upper[t].waist[1]));
  }
  EXPECT_GT(erect_hits, 5) << "an erect torso would have passed: the test proves nothing";
  EXPECT_GT(max_turn, 0.3f) << "the waist did not turn";
  EXPECT_EQ(colliding_frames(r, scene, body), 0);
}

TEST(UpperBody, AChestHighWallStopsTheActorWithAClearFailure) {
  // Bottom at 0.9 m: the legs pass under it (not in the ground profile), the torso cannot.
  const Scene scene = flat_scene({box({-2.0f, 0.9f, 3.0f}, {2.0f, 2.5f, 3.3f})});
  auto walker = make_walker();
  const WalkRecord r = walk(*walker, scene, GroundPath{{0.0f, 0.0f}, 0.0f, 0.0f}, 6.0f);
  EXPECT_EQ(r.last, TerrainStepStatus::kUpperBodyFailed);
  const UpperBodyPlan& plan = walker->upper_plan;
  EXPECT_TRUE(plan.status == UpperBodyStatus::kNoPath || plan.status == UpperBodyStatus::kBudget)
      << upper_body_status_name(plan.status);
  EXPECT_EQ(plan.failed_part, BodyPart::kWaist);
  EXPECT_EQ(plan.num_frames, 0);
  ASSERT_FALSE(r.pelvis.empty());
  EXPECT_LT(r.pelvis.back().pos_m.z, 3.0f);
  EXPECT_EQ(colliding_frames(r, scene, walker->config.upper_body.body), 0);
  for (const UpperBodyConfig& c : r.upper) EXPECT_TRUE(finite(c));
  // Stopped, not stuck: the actor still steers away (a path to the side plans fine).
  EXPECT_TRUE(terrain_walker_start(*walker, scene,
                                   GroundPath{ground(r.pelvis.back().pos_m), -kPi / 2, 0.0f}, 4.0f));
  EXPECT_EQ(terrain_walker_step(*walker, scene), TerrainStepStatus::kOk);
}

TEST(UpperBody, BadInputGetsAClearStatus) {
  UpperBodyPlanner planner;
  UpperBodyPlannerConfig bad;
  bad.max_checks_per_part = 0;
  EXPECT_FALSE(upper_body_planner_init(planner, bad));
  UpperBodyPlannerConfig thin;  // arms of 1 mm radius would need more spheres than a part holds
  thin.body.upper_arm_radius_m = thin.body.forearm_radius_m = 0.001f;
  thin.body.margin_m = 0.0f;
  EXPECT_FALSE(upper_body_planner_init(planner, thin));
  auto plan = std::make_unique<UpperBodyPlan>();
  UpperBodyObstacles none;
  std::vector<PelvisFrame> track(10);
  for (size_t t = 0; t < track.size(); ++t) track[t].pos_m = vec3(0.0f, 0.95f, 0.04f * static_cast<float>(t));
  EXPECT_EQ(upper_body_plan(planner, track, 1 / 30.0f, none, {}, *plan), UpperBodyStatus::kInvalidConfig);
  ASSERT_TRUE(upper_body_planner_init(planner, UpperBodyPlannerConfig{}));
  EXPECT_EQ(upper_body_plan(planner, {}, 1 / 30.0f, none, {}, *plan), UpperBodyStatus::kBadInput);
  EXPECT_EQ(upper_body_plan(planner, track, 0.0f, none, {}, *plan), UpperBodyStatus::kBadInput);
  std::vector<PelvisFrame> nan_track = track;
  nan_track[4].pos_m.y = NAN;
  EXPECT_EQ(upper_body_plan(planner, nan_track, 1 / 30.0f, none, {}, *plan), UpperBodyStatus::kBadInput);
  UpperBodyConfig nan_start;
  nan_start.arms[1][2] = NAN;
  EXPECT_EQ(upper_body_plan(planner, track, 1 / 30.0f, none, nan_start, *plan), UpperBodyStatus::kBadInput);
  // A box around the head at frame 0.
  const Scene scene = flat_scene({box({-0.3f, 1.5f, -0.3f}, {0.3f, 1.9f, 0.3f})});
  UpperBodyObstacles head_box;
  gather_upper_body_obstacles(scene, track, 1.0f, 0.5f, head_box);
  ASSERT_EQ(head_box.count, 1);
  EXPECT_EQ(upper_body_plan(planner, track, 1 / 30.0f, head_box, {}, *plan), UpperBodyStatus::kStartInCollision);
  EXPECT_EQ(plan->failed_part, BodyPart::kWaist);
  EXPECT_EQ(plan->num_frames, 0);
  UpperBodyObstacles overflow;
  overflow.overflow = true;
  EXPECT_EQ(upper_body_plan(planner, track, 1 / 30.0f, overflow, {}, *plan), UpperBodyStatus::kTooManyObstacles);
  // More boxes near the path than fit: reported, not silently cut.
  std::vector<SceneBox> many;
  for (int i = 0; i < UpperBodyObstacles::kCapacity + 1; ++i)
    many.push_back(box({1.0f, 1.0f, 0.02f * static_cast<float>(i)}, {1.01f, 1.2f, 0.02f * static_cast<float>(i) + 0.01f}));
  UpperBodyObstacles gathered;
  gather_upper_body_obstacles(flat_scene(many), track, 1.5f, 0.5f, gathered);
  EXPECT_TRUE(gathered.overflow);
}

TEST(UpperBody, SameInputSamePlan) {
  Scene scene;
  std::string error;
  ASSERT_TRUE(scene_load(scene_path("terrain"), scene, error)) << error;
  auto a = make_walker(), b = make_walker();
  const GroundPath path{{11.0f, 15.0f}, kPi / 2, 0.0f};
  const WalkRecord ra = walk(*a, scene, path, 4.0f), rb = walk(*b, scene, path, 4.0f);
  ASSERT_EQ(ra.upper.size(), rb.upper.size());
  ASSERT_FALSE(ra.upper.empty());
  EXPECT_EQ(std::memcmp(ra.upper.data(), rb.upper.data(), ra.upper.size() * sizeof(UpperBodyConfig)), 0);
  for (int p = 0; p < 3; ++p) {
    EXPECT_EQ(a->upper_plan.parts[static_cast<size_t>(p)].checks, b->upper_plan.parts[static_cast<size_t>(p)].checks);
    EXPECT_EQ(a->upper_plan.parts[static_cast<size_t>(p)].grown, b->upper_plan.parts[static_cast<size_t>(p)].grown);
  }
}

TEST(UpperBody, ThePelvisTrackFollowsTheFootstepPlan) {
  auto walker = make_walker();
  const Scene scene = flat_scene();
  ASSERT_TRUE(terrain_walker_start(*walker, scene, GroundPath{{1.0f, 2.0f}, kPi / 2, 0.0f}, 8.0f));
  ASSERT_EQ(terrain_walker_step(*walker, scene), TerrainStepStatus::kOk);
  const int n = walker->track_frames;
  ASSERT_GT(n, 3 * 10);
  EXPECT_GT(walker->step_frames, 5);
  EXPECT_LT(walker->step_frames, n);
  const float dt = walker->config.dt_s;
  for (int t = 1; t < n; ++t) {
    const PelvisFrame& f0 = walker->track[static_cast<size_t>(t - 1)];
    const PelvisFrame& f1 = walker->track[static_cast<size_t>(t)];
    EXPECT_NEAR(f1.pos_m.z, 2.0f, 1e-4f);   // heading east: z constant
    EXPECT_GT(f1.pos_m.x, f0.pos_m.x - 1e-4f);
    EXPECT_LT(f1.pos_m.x - f0.pos_m.x, 3.0f * walker->config.speed_mps * dt);
    EXPECT_NEAR(f1.heading_rad, kPi / 2, 1e-5f);
    EXPECT_GT(f1.pos_m.y, 0.8f);
  }
  // Step 1 swings the left leg: its thigh ends forward, the right one back.
  const PelvisFrame& end = walker->track[static_cast<size_t>(walker->step_frames)];
  EXPECT_GT(end.left_hip_rad, 0.0f);
  EXPECT_LT(end.right_hip_rad, 0.0f);
}

}  // namespace
}  // namespace foresight::terrain

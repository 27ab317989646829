// The motion-quality measurement (issue 18) on a real closed loop: without the pose stage root
// steering slides planted feet and pops; with it the feet stay planted, the turn is eased, and
// the navigation (response, goals, collisions) is the same, because the stage only changes what
// is shown.
#include "lab/motion_quality.hpp"
#include "lab/lab_experiments.hpp"
#include "import/bvh.hpp"
#include "library_build/library_source.hpp"
#include "library/foreign_capture.hpp"
#include "support/bvh_variants.hpp"
#include "support/test_paths.hpp"
#include "world/data_paths.hpp"

#include <gtest/gtest.h>

namespace foresight::lab {
namespace {

const float kSteerRadPerS = radians(kLabSteerDegPerS);  // the lab's and the server's default

// The three controllers' results (the paper's, steering raw, steering + pose stage).
std::vector<MotionQualityResult> measure(const MotionLibrary& lib, const Scene& scene, const CollisionWorld& world,
                                         const MotionQualityOptions& options) {
  std::string error;
  std::vector<MotionQualityResult> r =
      measure_motion_quality(lib, scene, world, motion_quality_controllers(kSteerRadPerS), options, error);
  EXPECT_EQ(r.size(), 3u) << error;
  return r;
}

// The same with the built-in library on `scene_name`'s first spawn to its first goal, player
// seeds 1..seeds, at most 60 s each.
std::vector<MotionQualityResult> measure(const char* scene_name, int seeds) {
  const MotionLibrary lib = motion_library_default();
  Scene scene;
  CollisionWorld world;
  std::string error;
  EXPECT_TRUE(scene_world_load(scene_name, scene, world, error)) << error;
  MotionQualityOptions options;
  options.seeds = seeds;
  options.max_seconds = 60;
  return measure(lib, scene, world, options);
}

TEST(MotionQuality, ThePoseStageKeepsSteeredFeetPlantedAndChangesNothingElse) {
  const auto controllers = motion_quality_controllers(kSteerRadPerS);
  ASSERT_EQ(controllers.size(), 3u);
  ASSERT_FALSE(controllers[1].pose_stage);
  ASSERT_TRUE(controllers[2].pose_stage);
  const std::vector<MotionQualityResult> r = measure("maze", 1);
  ASSERT_EQ(r.size(), 3u);
  const MotionQualityResult& raw = r[1];
  const MotionQualityResult& staged = r[2];
  EXPECT_GT(raw.contact_samples, 300);
  EXPECT_GT(raw.foot_skate_cm_per_s_p95, 10.0) << "steering slides planted feet";
  EXPECT_LT(staged.foot_skate_cm_per_s_p95, 2.0) << "the stage keeps them planted";
  EXPECT_LT(staged.pops, raw.pops) << "and eases the turn";
  EXPECT_GT(raw.added_pops, raw.pops / 2) << "raw steering's pops are its own, not the clips'";
  EXPECT_LT(staged.added_pops, raw.added_pops / 4);
  // A foot the stage lets go of (a step steering forces, a lift) sets off from rest: with the
  // stage before that, 3.4 pops a minute on this seed; 0 now (docs/MOTION_QUALITY.md, "Pops at
  // stops, steps and landings").
  EXPECT_LT(staged.pops_per_min, 1.0);
  for (const MotionQualityResult& x : r) EXPECT_LE(x.added_pops, x.pops);
  EXPECT_EQ(raw.limit_violations, 0) << "played poses never violate";
  EXPECT_LE(staged.limit_violations, 3);
  EXPECT_EQ(staged.collisions, 0);
  EXPECT_EQ(staged.goals_reached, raw.goals_reached);
  EXPECT_EQ(staged.response_ms_p95, raw.response_ms_p95) << "what is shown does not steer";
}

// Graph avatars on the terrain scene (its route climbs a 0.18 m step onto a second one, over
// rolling slopes): flat-ground clips shown by the stage keep their planted feet on the ground
// under them, where the raw playback floats or sinks by the step's height.
TEST(MotionQuality, OnUnevenGroundThePlantedFeetAreOnTheGround) {
  const std::vector<MotionQualityResult> r = measure("terrain", 2);
  ASSERT_EQ(r.size(), 3u);
  const MotionQualityResult& raw = r[1];
  const MotionQualityResult& staged = r[2];
  EXPECT_GT(raw.ground_error_cm_max, 15.0) << "the route crosses the steps: raw feet are off the ground there";
  EXPECT_LT(staged.ground_error_cm_p95, 2.0);
  EXPECT_LT(staged.ground_error_cm_max, raw.ground_error_cm_max / 2.0);
  EXPECT_LT(staged.foot_skate_cm_per_s_p95, 2.0);
  EXPECT_LE(staged.pops, raw.pops / 4);
  EXPECT_EQ(staged.collisions, 0);
  EXPECT_EQ(staged.goals_reached, raw.goals_reached);
}

// Up the two steps to `stairs-top`, every planted frame (not only 95 % of them) has its planted
// part within 2 cm of the ground under it: a swinging foot goes to the height of the ground it
// will land on, a part landing on or creeping over a step's edge is put on the step it stands on,
// a ball held behind the body at push-off lifts the heel instead of being dragged, and landings
// near edges add no pops. Also with the
// steps moved 5 cm back and 3, 7 and 15 cm on (levels nobody tuned the stage for: the feet land
// elsewhere against the edges).
TEST(MotionQuality, UpTheStairsEveryPlantedFootIsOnTheGroundWhereverTheEdgesAre) {
  const MotionLibrary lib = motion_library_default();
  for (const float shift_m : {0.0f, -0.05f, 0.03f, 0.07f, 0.15f}) {
    Scene scene;
    CollisionWorld world;
    std::string error;
    ASSERT_TRUE(scene_world_load("terrain", scene, world, error)) << error;
    ASSERT_EQ(scene.terrain.steps.size(), 2u);
    ASSERT_TRUE(shift_steps(scene, world, shift_m, error)) << error;
    MotionQualityOptions options;
    options.seeds = 5;
    options.goal = "stairs-top";
    options.max_seconds = 60;
    const std::vector<MotionQualityResult> r = measure(lib, scene, world, options);
    ASSERT_EQ(r.size(), 3u);
    const MotionQualityResult& raw = r[1];
    const MotionQualityResult& staged = r[2];
    SCOPED_TRACE(shift_m);
    EXPECT_GT(raw.ground_error_cm_max, 30.0) << "raw feet stand on the clip's floor, inside the upper step";
    EXPECT_LT(staged.ground_error_cm_max, 2.0);
    EXPECT_LT(staged.foot_skate_cm_per_s_p95, 2.0);
    EXPECT_LT(staged.foot_skate_cm_per_s_max, 10.0);
    EXPECT_EQ(staged.goals_reached, 5);
    EXPECT_EQ(staged.collisions, 0);
    EXPECT_EQ(staged.limit_violations, 0);
    // A foot that will land on an edge goes to its foothold while it swings, and one that must
    // climb a step it found late climbs over the rest of the swing: no jump on the first frame
    // down (with the steps 5 cm back that gave 6.1 pops a minute here, twice the others' 3.0).
    // A landing that steering turns onto the upper step in the swing's last two frames is
    // climbed to at a bounded acceleration and lands late: without that, 12.1 and 9.1 a minute
    // with the steps 5 cm back and 15 cm on (docs/MOTION_QUALITY.md). No pop in the five runs:
    // a landing the turn sweeps comes to rest over two frames (PoseStage::touch_down); before,
    // two of them had a pop (with the steps 5 cm back, a landing at 122 mm/frame^2; on 30 seeds
    // 9.8-12.8 pops a minute by shift, now 0-0.5). Since steering keeps within the clips' room
    // (the pop budget), one marginal pop in these runs (122 mm/frame^2 against 121, steps 15 cm
    // on): a wrong-key tap reversed the turn two frames before a segment switch, which stops it
    // (docs/MOTION_QUALITY.md, "Steering within the clips' room"). Not a landing.
    EXPECT_LE(staged.added_pops, 1);
  }
}

// Closed loop on capture the team did not make, made more foreign still: every Bandai locomotion
// take rescaled to inches under a dummy root, written to disk and compiled with no unit hint, as
// a studio's export would arrive. Through the maze the pose stage holds the aims it holds on the
// built-in library: planted feet under 2 cm/s at p95 where raw steering slides them, fewer pops
// than raw and few of them added, no limit violation, no colliding frame, every goal the raw
// controller reaches, and the same response; and the default controller's figures are those of
// the takes as captured (measured: the same to the digit).
TEST(MotionQuality, OnACaptureInInchesUnderADummyRootTheStageHoldsItsAimsClosedLoop) {
  FORESIGHT_REQUIRE_MOCAP();
  MotionLibrary lib;
  ASSERT_NO_FATAL_FAILURE(test::foreign_locomotion_library(lib));
  std::string error;
  Scene scene;
  CollisionWorld world;
  ASSERT_TRUE(scene_world_load("maze", scene, world, error)) << error;
  MotionQualityOptions options;
  options.seeds = 2;
  options.max_seconds = 120;
  const std::vector<MotionQualityResult> r = measure(lib, scene, world, options);
  ASSERT_EQ(r.size(), 3u);
  const MotionQualityResult& raw = r[1];
  const MotionQualityResult& staged = r[2];
  EXPECT_GT(raw.goals_reached, 0);
  EXPECT_EQ(staged.goals_reached, raw.goals_reached);
  EXPECT_GT(raw.foot_skate_cm_per_s_p95, 10.0) << "steering slides the capture's planted feet";
  EXPECT_LT(staged.foot_skate_cm_per_s_p95, 2.0);
  EXPECT_LT(staged.foot_skate_cm_per_s_max, 10.0);
  EXPECT_LT(staged.pops, raw.pops / 4);
  EXPECT_LT(staged.added_pops_per_min, 10.0);
  EXPECT_EQ(staged.limit_violations, 0);
  EXPECT_EQ(staged.collisions, 0);
  EXPECT_EQ(staged.response_ms_p95, raw.response_ms_p95);
  EXPECT_EQ(staged.shown_response_ms_p95, staged.response_ms_p95) << "the shown body answers with the root";
  // The count behind the p95: the paper's controller (p95 far over 250 ms) has more than 5 % of
  // its responses over the aim; the stage changes neither the responses nor how many are slow.
  EXPECT_GT(r[0].response_ms_p95, kResponseAim_ms);
  EXPECT_GT(r[0].responses_over_aim * 20, r[0].responses);
  EXPECT_GT(staged.responses, 0);
  EXPECT_EQ(staged.responses, raw.responses);
  EXPECT_EQ(staged.responses_over_aim, raw.responses_over_aim);
  EXPECT_LE(staged.responses_over_aim, staged.responses);

  MotionSource source;
  source.motions_dir = test::mocap_dir() / "locomotion";
  MotionLibrary captured;
  ASSERT_TRUE(motion_library_from_folder(source, captured, nullptr, error)) << error;
  const std::vector<MotionQualityResult> c = measure(captured, scene, world, options);
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(staged.goals_reached, c[2].goals_reached);
  EXPECT_NEAR(staged.foot_skate_cm_per_s_p95, c[2].foot_skate_cm_per_s_p95, 0.05);
  EXPECT_NEAR(staged.ground_error_cm_max, c[2].ground_error_cm_max, 0.2);
  EXPECT_NEAR(staged.pops_per_min, c[2].pops_per_min, 1.0);
  EXPECT_EQ(staged.response_ms_p95, c[2].response_ms_p95);
}

// A level of the size designers draw that the stage was not tuned on: three 0.9 m doors offset
// left, right, left, taken with side steps and turns. Planted feet stay planted, nothing shown
// collides, no limit is broken, the stage takes no goal away and fewer pops are shown than raw.
TEST(MotionQuality, ThroughNarrowOffsetDoorsThePlantedFeetStayAndNothingCollides) {
  const std::vector<MotionQualityResult> r = measure("doorways", 2);
  ASSERT_EQ(r.size(), 3u);
  const MotionQualityResult& raw = r[1];
  const MotionQualityResult& staged = r[2];
  EXPECT_GT(raw.goals_reached, 0);
  EXPECT_EQ(staged.goals_reached, raw.goals_reached);
  EXPECT_GT(raw.foot_skate_cm_per_s_p95, 10.0);
  EXPECT_LT(staged.foot_skate_cm_per_s_p95, 2.0);
  EXPECT_LT(staged.foot_skate_cm_per_s_max, 10.0);
  EXPECT_LT(staged.pops, raw.pops / 4);
  EXPECT_EQ(staged.limit_violations, 0);
  EXPECT_EQ(staged.collisions, 0);
}

}  // namespace
}  // namespace foresight::lab

// The procedural walk (paper 4.1): footholds, key frames by category (Fig. 4), the swing curve.
#include "terrain_test_util.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace foresight::terrain {
namespace {

Foothold fit(const GroundProfile& profile, float x) {
  Foothold f;
  EXPECT_EQ(foothold_fit(profile, WalkParams{}, x, f), WalkStatus::kOk) << x;
  return f;
}

WalkStep plan_step(const GroundProfile& profile, float rear, float stance, float land) {
  WalkStep step;
  EXPECT_EQ(walk_step_plan(profile, WalkParams{}, fit(profile, rear), fit(profile, stance),
                           fit(profile, land), step),
            WalkStatus::kOk);
  return step;
}

TEST(ProceduralWalk, DefaultSkeletonGivesTheDefaultParams) {
  const WalkParams p = walk_params_from_default_skeleton();
  const WalkParams d;
  EXPECT_FLOAT_EQ(p.thigh_m, d.thigh_m);
  EXPECT_FLOAT_EQ(p.shin_m, d.shin_m);
  EXPECT_NEAR(p.ankle_height_m, d.ankle_height_m, 1e-5f);
  EXPECT_NEAR(p.toe_front_m, d.toe_front_m, 1e-5f);
  EXPECT_NEAR(p.hip_below_pelvis_m, d.hip_below_pelvis_m, 1e-5f);
}

TEST(ProceduralWalk, FootholdsOnFlatSlopeEdgeAndGap) {
  GroundProfile profile;
  ground_profile_flat(profile, 6.0f, 0.1f);
  Foothold f;
  ASSERT_EQ(foothold_fit(profile, WalkParams{}, 1.0f, f), WalkStatus::kOk);
  EXPECT_NEAR(f.sole_y_m, 0.1f, 1e-5f);
  EXPECT_NEAR(f.pitch_rad, 0.0f, 1e-6f);
  // A slope of 0.2: the sole pitches with it and sits on it.
  ground_profile_ramp(profile, 2.0f, 6.0f, 0.1f, 0.9f);
  ASSERT_EQ(foothold_fit(profile, WalkParams{}, 4.0f, f), WalkStatus::kOk);
  EXPECT_NEAR(f.pitch_rad, std::atan(0.2f), 0.02f);
  EXPECT_NEAR(f.sole_y_m, 0.1f + 0.2f * 2.0f, 0.02f);
  // An edge under the foot, a gap under the toe, off the profile.
  GroundProfile edge;
  ground_profile_flat(edge, 6.0f, 0.0f);
  ground_profile_fill(edge, 2.0f, 6.0f, 0.18f);
  EXPECT_EQ(foothold_fit(edge, WalkParams{}, 1.95f, f), WalkStatus::kFootholdUneven);
  ground_profile_fill(edge, 3.0f, 3.2f, std::numeric_limits<float>::quiet_NaN());
  EXPECT_EQ(foothold_fit(edge, WalkParams{}, 2.9f, f), WalkStatus::kFootInGap);
  EXPECT_EQ(foothold_fit(edge, WalkParams{}, 5.95f, f), WalkStatus::kOutsideProfile);
  EXPECT_EQ(foothold_fit(edge, WalkParams{}, std::numeric_limits<float>::quiet_NaN(), f),
            WalkStatus::kOutsideProfile);
}

TEST(ProceduralWalk, LevelUphillDownhillKeyFrames) {
  GroundProfile profile;
  ground_profile_flat(profile, 6.0f, 0.0f);
  ground_profile_fill(profile, 2.4f, 6.0f, 0.18f);
  const WalkStep level = plan_step(profile, 0.7f, 1.35f, 2.0f);
  const WalkStep up = plan_step(profile, 1.35f, 2.0f, 2.65f);    // Onto the block.
  const WalkStep after_up = plan_step(profile, 2.0f, 2.65f, 3.3f);
  EXPECT_EQ(level.kind, StepKind::kLevel);
  EXPECT_EQ(up.kind, StepKind::kUphill);
  EXPECT_EQ(after_up.kind, StepKind::kLevel);
  // Uphill: the front leg bends first. At landing the front (swing) knee is bent more than on the
  // level and more than the rear (stance) knee; the pelvis stays at the lower level's height and
  // rises over the next step.
  EXPECT_GT(up.keys[2].swing.knee_rad, level.keys[2].swing.knee_rad + 0.2f);
  EXPECT_GT(up.keys[2].swing.knee_rad, up.keys[2].stance.knee_rad);
  EXPECT_NEAR(up.keys[2].pelvis_m.y, level.keys[2].pelvis_m.y, 0.02f);
  EXPECT_GT(after_up.keys[1].pelvis_m.y, up.keys[2].pelvis_m.y + 0.1f);

  GroundProfile down_profile;
  ground_profile_flat(down_profile, 6.0f, 0.18f);
  ground_profile_fill(down_profile, 2.4f, 6.0f, 0.0f);
  const WalkStep down = plan_step(down_profile, 1.35f, 2.0f, 2.65f);  // Off the block.
  EXPECT_EQ(down.kind, StepKind::kDownhill);
  // Downhill: the rear (stance) leg bends first: its knee flexes in the passing frame, lowering the
  // pelvis before the front foot lands, and at landing it is the more bent leg.
  EXPECT_GT(down.keys[1].stance.knee_rad, level.keys[1].stance.knee_rad + 0.1f);
  EXPECT_LT(down.keys[1].pelvis_m.y - 0.18f, level.keys[1].pelvis_m.y - 0.05f);
  EXPECT_GT(down.keys[2].stance.knee_rad, down.keys[2].swing.knee_rad);
}

TEST(ProceduralWalk, SlopesChooseUphillAndDownhillKeyFrames) {
  FootstepPlanner planner;
  ASSERT_TRUE(footstep_planner_init(planner, FootstepPlannerConfig{}));
  // Gradient 0.15: every neutral step rises ~0.1 m (> the 0.04 m level threshold).
  GroundProfile up;
  ground_profile_flat(up, 12.0f, 0.0f);
  ground_profile_ramp(up, 1.6f, 12.0f, 0.0f, 0.15f * 10.4f);
  auto log = test::walk_with_planner(planner, up, 0.5f, 8.0f);
  ASSERT_EQ(log.last_status, FootstepStatus::kOk) << footstep_status_name(log.last_status);
  int uphill = 0, on_slope = 0;
  for (const WalkStep& s : log.steps) {
    if (s.stance.x_m < 2.2f) continue;  // Still on the flat start.
    ++on_slope;
    uphill += s.kind == StepKind::kUphill;
    EXPECT_LE(test::swing_penetration_m(up, planner.config.walk, s), 0.005f);
  }
  EXPECT_GT(on_slope, 5);
  EXPECT_EQ(uphill, on_slope);

  GroundProfile down;
  ground_profile_flat(down, 12.0f, 2.0f);
  ground_profile_ramp(down, 1.6f, 12.0f, 2.0f, 2.0f - 0.15f * 10.4f);
  log = test::walk_with_planner(planner, down, 0.5f, 8.0f);
  ASSERT_EQ(log.last_status, FootstepStatus::kOk) << footstep_status_name(log.last_status);
  int downhill = 0;
  on_slope = 0;
  for (const WalkStep& s : log.steps) {
    if (s.stance.x_m < 2.2f) continue;
    ++on_slope;
    downhill += s.kind == StepKind::kDownhill;
    EXPECT_LE(test::swing_penetration_m(down, planner.config.walk, s), 0.005f);
  }
  EXPECT_GT(on_slope, 5);
  EXPECT_EQ(downhill, on_slope);

  // A gentle 0.03 gradient stays level.
  GroundProfile gentle;
  ground_profile_flat(gentle, 12.0f, 0.0f);
  ground_profile_ramp(gentle, 1.6f, 12.0f, 0.0f, 0.03f * 10.4f);
  log = test::walk_with_planner(planner, gentle, 0.5f, 8.0f);
  ASSERT_EQ(log.last_status, FootstepStatus::kOk);
  for (const WalkStep& s : log.steps) EXPECT_EQ(s.kind, StepKind::kLevel);
}

TEST(ProceduralWalk, SwingCurveLiftsOverAnObstacleOrFails) {
  GroundProfile profile;
  ground_profile_flat(profile, 6.0f, 0.0f);
  ground_profile_fill(profile, 1.95f, 2.05f, 0.25f);  // A 25 cm log between stance and landing.
  const WalkStep step = plan_step(profile, 1.0f, 1.6f, 2.4f);
  EXPECT_GT(step.lift_m, 0.25f);
  EXPECT_LE(test::swing_penetration_m(profile, WalkParams{}, step), 0.005f);
  // Mid-swing the whole (level) sole is above the log.
  WalkFrame f;
  walk_step_sample(step, WalkParams{}, 0.75f, f);
  EXPECT_TRUE(std::isfinite(f.pelvis_m.y));
  // A 1 m post cannot be swung over.
  ground_profile_fill(profile, 1.95f, 2.05f, 1.0f);
  WalkStep high;
  EXPECT_EQ(walk_step_plan(profile, WalkParams{}, fit(profile, 1.0f), fit(profile, 1.6f),
                           fit(profile, 2.4f), high),
            WalkStatus::kNoClearance);
}

TEST(ProceduralWalk, HeightLimitsAndSampling) {
  GroundProfile profile;
  ground_profile_flat(profile, 6.0f, 0.0f);
  ground_profile_fill(profile, 2.4f, 6.0f, 0.6f);
  WalkStep step;
  EXPECT_EQ(walk_step_plan(profile, WalkParams{}, fit(profile, 1.35f), fit(profile, 2.0f),
                           fit(profile, 2.65f), step),
            WalkStatus::kStepTooHigh);
  ground_profile_fill(profile, 2.4f, 6.0f, -0.6f);
  EXPECT_EQ(walk_step_plan(profile, WalkParams{}, fit(profile, 1.35f), fit(profile, 2.0f),
                           fit(profile, 2.65f), step),
            WalkStatus::kStepTooLow);
  // Sampling: the stance ankle stays planted, the swing ankle starts and ends on its footholds,
  // the pelvis is continuous between consecutive steps (K2 of one = K0 of the next).
  ground_profile_flat(profile, 6.0f, 0.0f);
  const WalkParams p;
  const WalkStep a = plan_step(profile, 0.7f, 1.35f, 2.0f);
  const WalkStep b = plan_step(profile, 1.35f, 2.0f, 2.6f);
  WalkFrame f0, f1, g0;
  walk_step_sample(a, p, 0.0f, f0);
  walk_step_sample(a, p, 1.0f, f1);
  walk_step_sample(b, p, 0.0f, g0);
  EXPECT_NEAR(f0.swing_ankle_m.x, 0.7f, 1e-3f);
  EXPECT_NEAR(f1.swing_ankle_m.x, 2.0f, 1e-3f);
  EXPECT_NEAR(f1.swing_ankle_m.y, p.ankle_height_m, 1e-3f);
  EXPECT_NEAR(f1.pelvis_m.x, g0.pelvis_m.x, 1e-3f);
  EXPECT_NEAR(f1.pelvis_m.y, g0.pelvis_m.y, 1e-3f);
  for (float t = 0.0f; t <= 1.0f; t += 0.05f) {
    WalkFrame f;
    walk_step_sample(a, p, t, f);
    EXPECT_NEAR(f.stance_ankle_m.x, 1.35f, 1e-5f);
    EXPECT_GT(f.pelvis_m.y, 0.8f);
    EXPECT_LT(f.pelvis_m.y, 0.98f);
  }
  WalkFrame nan_frame;
  walk_step_sample(a, p, std::numeric_limits<float>::quiet_NaN(), nan_frame);
  EXPECT_TRUE(std::isfinite(nan_frame.pelvis_m.x));
}

}  // namespace
}  // namespace foresight::terrain

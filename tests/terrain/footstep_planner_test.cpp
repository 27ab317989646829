// The footstep planner (paper 4.2): the Fig. 8 comparison, a raised block, and clear failures.
#include "terrain_test_util.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace foresight::terrain {
namespace {

using test::foot_in_gap;
using test::swing_penetration_m;
using test::walk_with_planner;

FootstepPlanner default_planner() {
  FootstepPlanner planner;
  EXPECT_TRUE(footstep_planner_init(planner, FootstepPlannerConfig{}));
  return planner;
}

// Flat 10 m with a 0.5 m gap placed where the fourth fixed 0.65 m step from 1.0 m lands (3.6 m).
GroundProfile fig8_profile() {
  GroundProfile profile;
  ground_profile_flat(profile, 10.0f, 0.0f);
  ground_profile_fill(profile, 3.45f, 3.95f, std::numeric_limits<float>::quiet_NaN());
  return profile;
}

TEST(FootstepPlanner, Fig8FixedStepLengthFallsIntoTheGap) {
  const GroundProfile profile = fig8_profile();
  const WalkParams params;
  FootstepWindow window;
  window.rear_x_m = window.stance_x_m = 1.0f;
  WalkStatus status = WalkStatus::kOk;
  int steps = 0;
  for (; steps < 20 && window.stance_x_m < 5.0f; ++steps) {
    WalkStep step;
    status = fixed_step_advance(profile, params, 0.65f, window, step);
    if (status != WalkStatus::kOk) break;
  }
  EXPECT_EQ(status, WalkStatus::kFootInGap) << walk_status_name(status);
  EXPECT_EQ(steps, 3);  // 1.65, 2.3, 2.95 fine; 3.6 is in the gap: the trap of Fig. 8(a).
  EXPECT_LT(window.stance_x_m, 3.45f);
}

TEST(FootstepPlanner, Fig8PlannerStridesOverTheGap) {
  const GroundProfile profile = fig8_profile();
  FootstepPlanner planner = default_planner();
  const auto log = walk_with_planner(planner, profile, 1.0f, 6.0f);
  ASSERT_EQ(log.last_status, FootstepStatus::kOk) << footstep_status_name(log.last_status);
  EXPECT_FALSE(log.non_finite);
  bool crossed = false;
  for (const WalkStep& s : log.steps) {
    EXPECT_FALSE(foot_in_gap(profile, planner.config.walk, s.land.x_m)) << s.land.x_m;
    EXPECT_LE(swing_penetration_m(profile, planner.config.walk, s), 0.005f);
    if (s.stance.x_m < 3.45f && s.land.x_m > 3.95f) {
      crossed = true;
      // Heel beyond the gap, toe of the stance foot before it: a stride of >= 0.5 m + foot.
      EXPECT_GE(s.land.x_m - s.stance.x_m, 0.5f + planner.config.walk.heel_back_m +
                                               planner.config.walk.toe_front_m - 0.02f);
    }
  }
  EXPECT_TRUE(crossed);
}

TEST(FootstepPlanner, StepsOntoARaisedBlockAndDownAgain) {
  GroundProfile profile;
  ground_profile_flat(profile, 10.0f, 0.0f);
  ground_profile_fill(profile, 3.0f, 5.0f, 0.18f);
  FootstepPlanner planner = default_planner();
  const auto log = walk_with_planner(planner, profile, 1.0f, 7.0f);
  ASSERT_EQ(log.last_status, FootstepStatus::kOk) << footstep_status_name(log.last_status);
  EXPECT_FALSE(log.non_finite);
  int on_block = 0, up = 0, down = 0;
  for (const WalkStep& s : log.steps) {
    if (std::abs(s.land.sole_y_m - 0.18f) < 1e-3f) ++on_block;
    up += s.kind == StepKind::kUphill;
    down += s.kind == StepKind::kDownhill;
    EXPECT_LE(swing_penetration_m(profile, planner.config.walk, s), 0.005f);
    // Never straddling the edge: the whole foot on one level.
    EXPECT_NEAR(s.land.pitch_rad, 0.0f, 1e-4f);
  }
  EXPECT_GE(on_block, 1);
  EXPECT_EQ(up, 1);
  EXPECT_EQ(down, 1);
}

TEST(FootstepPlanner, SlidingWindowReseedsWithTheRestOfThePlan) {
  GroundProfile profile;
  ground_profile_flat(profile, 10.0f, 0.0f);
  FootstepPlanner planner = default_planner();
  FootstepWindow window;
  window.rear_x_m = window.stance_x_m = 1.0f;
  FootstepPlan plan;
  ASSERT_EQ(footstep_plan(planner, profile, window, plan), FootstepStatus::kOk);
  // Flat ground: the neutral step everywhere, found at once (the seed is feasible and optimal).
  for (int i = 0; i < plan.num_steps; ++i)
    EXPECT_NEAR(plan.step_length_m[static_cast<std::size_t>(i)], 0.65f, 1e-4f);
  EXPECT_EQ(plan.bfs_expanded, 1);
  footstep_window_slide(planner, plan, window);
  EXPECT_FLOAT_EQ(window.rear_x_m, 1.0f);
  EXPECT_NEAR(window.stance_x_m, 1.65f, 1e-4f);
  EXPECT_TRUE(window.seeded);
  EXPECT_EQ(window.seed_index[0], plan.step_index[1]);
  EXPECT_EQ(window.seed_index[1], plan.step_index[2]);
  EXPECT_EQ(window.seed_index[2], planner.neutral_index);
}

TEST(FootstepPlanner, DeterministicCountersAndResults) {
  GroundProfile profile;
  ground_profile_random(profile, 7, 14.0f);
  FootstepPlanner a = default_planner(), b = default_planner();
  const auto la = walk_with_planner(a, profile, 0.5f, 10.0f);
  const auto lb = walk_with_planner(b, profile, 0.5f, 10.0f);
  ASSERT_EQ(la.plans.size(), lb.plans.size());
  EXPECT_EQ(la.last_status, lb.last_status);
  for (std::size_t i = 0; i < la.plans.size(); ++i) {
    EXPECT_EQ(la.plans[i].configs_evaluated, lb.plans[i].configs_evaluated);
    EXPECT_EQ(la.plans[i].step_index, lb.plans[i].step_index);
    EXPECT_EQ(la.plans[i].cost, lb.plans[i].cost);
  }
}

TEST(FootstepPlanner, SwingFootNeverBelowTheGroundOnSeededProfiles) {
  FootstepPlanner planner = default_planner();
  int steps = 0, walks_done = 0;
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    GroundProfile profile;
    ground_profile_random(profile, seed, 14.0f);
    const auto log = walk_with_planner(planner, profile, 0.5f, 10.0f);
    EXPECT_FALSE(log.non_finite) << seed;
    walks_done += log.last_status == FootstepStatus::kOk;
    for (const WalkStep& s : log.steps) {
      ++steps;
      EXPECT_LE(swing_penetration_m(profile, planner.config.walk, s), 0.005f) << "seed " << seed;
      EXPECT_FALSE(foot_in_gap(profile, planner.config.walk, s.land.x_m)) << "seed " << seed;
    }
  }
  EXPECT_GT(steps, 300);
  EXPECT_GE(walks_done, 20);  // Honest floor; the bench reports the real rate.
}

// --- Failures: clear, and never NaN or a crash --------------------------------------------------

TEST(FootstepPlanner, VerticalWallIsAClearFailure) {
  GroundProfile profile;
  ground_profile_flat(profile, 8.0f, 0.0f);
  ground_profile_fill(profile, 3.0f, 8.0f, 2.0f);
  FootstepPlanner planner = default_planner();
  const auto log = walk_with_planner(planner, profile, 1.0f, 7.0f);
  EXPECT_EQ(log.last_status, FootstepStatus::kWall) << footstep_status_name(log.last_status);
  EXPECT_FALSE(log.non_finite);
  for (const WalkStep& s : log.steps) EXPECT_LT(s.land.x_m + planner.config.walk.toe_front_m, 3.0f);
}

TEST(FootstepPlanner, CliffIsAClearFailure) {
  GroundProfile profile;
  ground_profile_flat(profile, 8.0f, 0.0f);
  ground_profile_fill(profile, 3.0f, 8.0f, -3.0f);
  FootstepPlanner planner = default_planner();
  const auto log = walk_with_planner(planner, profile, 1.0f, 7.0f);
  EXPECT_EQ(log.last_status, FootstepStatus::kCliff) << footstep_status_name(log.last_status);
  EXPECT_FALSE(log.non_finite);
  for (const WalkStep& s : log.steps) EXPECT_LT(s.land.x_m + planner.config.walk.toe_front_m, 3.0f);
}

TEST(FootstepPlanner, WideGapIsAClearFailure) {
  GroundProfile profile;
  ground_profile_flat(profile, 8.0f, 0.0f);
  ground_profile_fill(profile, 3.0f, 4.5f, std::numeric_limits<float>::quiet_NaN());
  FootstepPlanner planner = default_planner();
  const auto log = walk_with_planner(planner, profile, 1.0f, 7.0f);
  EXPECT_EQ(log.last_status, FootstepStatus::kGap) << footstep_status_name(log.last_status);
  EXPECT_FALSE(log.non_finite);
}

TEST(FootstepPlanner, EmptyAndBadInputsAreClearFailures) {
  FootstepPlanner planner = default_planner();
  FootstepPlan plan;
  FootstepWindow window;
  window.rear_x_m = window.stance_x_m = 1.0f;

  GroundProfile empty;
  EXPECT_EQ(footstep_plan(planner, empty, window, plan), FootstepStatus::kEmptyProfile);
  EXPECT_EQ(plan.num_steps, 0);

  GroundProfile holes;
  ground_profile_flat(holes, 5.0f, std::numeric_limits<float>::quiet_NaN());
  EXPECT_EQ(footstep_plan(planner, holes, window, plan), FootstepStatus::kBadStart);

  GroundProfile flat;
  ground_profile_flat(flat, 5.0f, 0.0f);
  FootstepWindow nan_window;
  nan_window.rear_x_m = nan_window.stance_x_m = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(footstep_plan(planner, flat, nan_window, plan), FootstepStatus::kBadStart);
  FootstepWindow outside;
  outside.rear_x_m = outside.stance_x_m = -3.0f;
  EXPECT_EQ(footstep_plan(planner, flat, outside, plan), FootstepStatus::kBadStart);

  // The window runs off a short profile.
  GroundProfile short_profile;
  ground_profile_flat(short_profile, 1.5f, 0.0f);
  EXPECT_EQ(footstep_plan(planner, short_profile, window, plan), FootstepStatus::kEndOfProfile);

  FootstepPlanner uninitialised;
  EXPECT_EQ(footstep_plan(uninitialised, flat, window, plan), FootstepStatus::kInvalidConfig);
  FootstepPlannerConfig bad;
  bad.window_steps = 0;
  EXPECT_FALSE(footstep_planner_init(uninitialised, bad));
  bad = FootstepPlannerConfig{};
  bad.step_max_m = bad.step_min_m;
  EXPECT_FALSE(footstep_planner_init(uninitialised, bad));
  bad = FootstepPlannerConfig{};
  bad.step_min_m = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FALSE(footstep_planner_init(uninitialised, bad));
  bad = FootstepPlannerConfig{};
  bad.intervals = kMaxStepIntervals + 1;
  EXPECT_FALSE(footstep_planner_init(uninitialised, bad));
}

}  // namespace
}  // namespace foresight::terrain

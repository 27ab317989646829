// The planners allocate only in their init: footstep planning, sliding, sampling and cutting a
// synthetic profile, and the upper-body planner and the walker stepping through the terrain
// scene, run with zero heap allocations (support/alloc_counter replaces the global operator new).
#include "terrain/terrain_walker.hpp"
#include "terrain_test_util.hpp"

#include "support/alloc_counter.hpp"
#include "world/data_paths.hpp"
#include "world/scene_load.hpp"

#include <gtest/gtest.h>

#include <memory>

namespace foresight::terrain {
namespace {

TEST(FootstepPlannerAllocation, NoHeapAllocationOnceInitialised) {
  FootstepPlanner planner;
  ASSERT_TRUE(footstep_planner_init(planner, FootstepPlannerConfig{}));
  static GroundProfile profile;  // 4 KiB: kept off the stack, allocated once.
  static FootstepPlan plan;
  int steps = 0;
  foresight::test::AllocationCount count;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    ground_profile_random(profile, seed, 14.0f);
    FootstepWindow window;
    window.rear_x_m = window.stance_x_m = 0.3f;
    while (window.stance_x_m < 10.0f &&
           footstep_plan(planner, profile, window, plan) == FootstepStatus::kOk) {
      WalkFrame frame;
      for (int k = 0; k <= 8; ++k) walk_step_sample(plan.steps[0], planner.config.walk, k / 8.0f, frame);
      footstep_window_slide(planner, plan, window);
      ++steps;
    }
  }
  EXPECT_EQ(count.allocations(), 0);
  EXPECT_GT(steps, 50);
}

TEST(TerrainWalkerAllocation, StepsThroughTheDoorwayWithoutAllocating) {
  Scene scene;
  std::string error;
  ASSERT_TRUE(scene_load(scene_path("terrain"), scene, error)) << error;
  auto walker = std::make_unique<TerrainWalker>();
  ASSERT_TRUE(terrain_walker_init(*walker, TerrainWalkerConfig{}));
  ASSERT_TRUE(terrain_walker_start(*walker, scene, GroundPath{{11.0f, 15.0f}, kPi / 2, 0.0f}, 6.0f));
  int steps = 0;
  {
    foresight::test::AllocationCount count;
    while (terrain_walker_travelled_m(*walker) < 4.0f && terrain_walker_step(*walker, scene) == TerrainStepStatus::kOk)
      ++steps;
    EXPECT_EQ(count.allocations(), 0);
  }
  EXPECT_GE(terrain_walker_travelled_m(*walker), 4.0f) << "stopped after " << steps << " steps";
}

}  // namespace
}  // namespace foresight::terrain

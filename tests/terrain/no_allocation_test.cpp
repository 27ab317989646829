// The planner allocates only in footstep_planner_init: planning, sliding, sampling and cutting a
// synthetic profile run with zero heap allocations (counted by replacing the global operator new
// in this test executable).
#include "terrain_test_util.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

// GCC sees free() on memory from "operator new" and warns, not knowing both are replaced here.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif

void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace foresight::terrain {
namespace {

TEST(FootstepPlannerAllocation, NoHeapAllocationOnceInitialised) {
  FootstepPlanner planner;
  ASSERT_TRUE(footstep_planner_init(planner, FootstepPlannerConfig{}));
  static GroundProfile profile;  // 4 KiB: kept off the stack, allocated once.
  static FootstepPlan plan;
  const long before = g_allocations.load();
  int steps = 0;
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
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_GT(steps, 50);
}

}  // namespace
}  // namespace foresight::terrain

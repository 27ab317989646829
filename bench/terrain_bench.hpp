#pragma once
// The terrain benchmark (decoupled footstep paper: 30 ms per step for the lower body on a 2.8 GHz
// P4; our aim is 300 us): the sliding-window footstep planner (n = 3, m = 13 by default) walking
// seeded paths, every plan call timed on the calling thread.
//
// The seeded set: paths cut from the terrain scene (random start and heading toward the gap and
// the hill, gently curving) plus seeded synthetic profiles (blocks, gaps, slopes, bumps;
// terrain::ground_profile_random). A scene path whose profile holds anything 0.7 m or more above
// the floor (a wall, the 0.8 m crate; the hill is 0.6 m), or whose start is not a foothold, is rejected before timing:
// walking into a wall is a correct failure, not a planner's. A walk starts with the feet together and succeeds when the stance
// foot has gone `walk_m` along the path; it fails at the first plan that fails.
// Collisions (must be 0): executed steps whose landing foot has a gap under it, or whose swing
// sole (heel, ankle, toe, 33 phases) goes more than 5 mm below the profile; and committed frames
// whose upper-body volumes touch a box.
//
// The upper body: whole-actor walks (terrain::TerrainWalker) through the low doorway, along the
// shelf and on random scene paths; each walker step's upper-body stage is timed alone.
#include "bench_json.hpp"
#include "terrain/upper_body_planner.hpp"

#include <array>
#include <cstdint>
#include <string>

namespace foresight::bench {

struct TerrainBenchOptions {
  std::string scene = "terrain";  ///< Built-in name or path.
  int scene_paths = 48;           ///< Accepted scene paths.
  int synthetic_profiles = 48;
  float walk_m = 7.0f;            ///< Scene paths; synthetic walks go 10 m.
  int window_steps = 3;           ///< n.
  int intervals = 13;             ///< m.
  int upper_body_walks = 48;      ///< Walks of the whole actor (footsteps + upper body).
  int upper_body_budget = terrain::UpperBodyPlannerConfig{}.max_checks_per_part;  ///< Checks per part.
  std::uint64_t seed = 1;
};

struct TerrainBenchResult {
  double footstep_plan_us_p50 = 0.0, footstep_plan_us_p99 = 0.0, footstep_plan_us_max = 0.0;
  double scene_plan_us_p50 = 0.0, synthetic_plan_us_p50 = 0.0;
  double profile_cut_us_p50 = 0.0;  ///< Cutting one scene path's profile (11 m, 3 lines).
  int paths = 0;            ///< Walks attempted (scene + synthetic).
  int paths_completed = 0;
  int scene_paths_rejected = 0;
  double success_rate = 0.0;  ///< paths_completed / paths.
  int plans = 0, plans_failed = 0;
  int steps = 0;            ///< Steps executed (first step of each successful plan).
  int collisions = 0;       ///< Must be 0.
  int non_finite = 0;       ///< Plans with a NaN/inf anywhere (must be 0).
  double configs_per_plan = 0.0, step_checks_per_plan = 0.0;
  std::array<int, 11> failures{};  ///< Failed walks by terrain::FootstepStatus.
  // The upper body (paper 5), planned along each committed window of whole-actor walks: through
  // the low doorway, along the shelf, and on random scene paths.
  double upper_body_plan_us_p50 = 0.0, upper_body_plan_us_p99 = 0.0, upper_body_plan_us_max = 0.0;
  int upper_body_plans = 0, upper_body_plans_failed = 0;
  int upper_body_walks = 0, upper_body_walks_completed = 0;  ///< Walks that were not stopped by the upper body.
  int upper_body_collisions = 0;  ///< Committed frames whose volumes touch a box (must be 0).
  double upper_body_checks_per_plan = 0.0;
  float max_waist_flexion_rad = 0.0f;  ///< Deepest bend seen (the doorway needs about 1.1).
  std::string error;        ///< Non-empty when the scene did not load.
};

/// Deterministic paths for a seed; the timings are wall-clock on the calling thread.
TerrainBenchResult run_terrain_bench(const TerrainBenchOptions& options);

/// {"footstep_plan_us_p50":...,"success_rate":...,"collisions":0,...}: the figures, rounded.
Json to_json(const TerrainBenchResult& result);

struct TerrainBenchCommand {
  TerrainBenchOptions options;
  bool json = false;
};
/// foresight-bench terrain: prints the machine, the figures and, with json, the JSON line.
int bench_terrain(const TerrainBenchCommand& command);

}  // namespace foresight::bench

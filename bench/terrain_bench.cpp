#include "terrain_bench.hpp"

#include "math/splitmix64.hpp"

#include "lab/lab_experiments.hpp"
#include "terrain/terrain_walker.hpp"
#include "world/data_paths.hpp"
#include "world/scene_load.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

namespace foresight::bench {
namespace {

using namespace foresight::terrain;
using Clock = std::chrono::steady_clock;



float ground_at(const GroundProfile& profile, float x) {
  float h = NAN;
  return profile.height_at(x, h) ? h : NAN;
}

bool step_collides(const GroundProfile& profile, const WalkParams& p, const WalkStep& step) {
  for (float x = step.land.x_m - p.heel_back_m; x <= step.land.x_m + p.toe_front_m; x += 0.01f)
    if (std::isnan(ground_at(profile, x))) return true;
  constexpr int kPhases = 32;
  for (int k = 0; k <= kPhases; ++k) {
    WalkFrame f;
    walk_step_sample(step, p, static_cast<float>(k) / kPhases, f);
    const vec2 sole = f.swing_ankle_m - vec2(0.0f, p.ankle_height_m);
    for (const vec2 q : {f.swing_heel_m, sole, f.swing_toe_m}) {
      const float g = ground_at(profile, q.x);
      if (!std::isnan(g) && q.y < g - 0.005f) return true;
    }
  }
  return false;
}

bool plan_finite(const FootstepPlan& plan) {
  bool ok = std::isfinite(plan.cost);
  for (int i = 0; i < plan.num_steps; ++i) {
    const WalkStep& s = plan.steps[static_cast<size_t>(i)];
    ok = ok && std::isfinite(s.lift_m) && std::isfinite(s.land.sole_y_m);
    for (const WalkKeyFrame& k : s.keys)
      ok = ok && std::isfinite(k.pelvis_m.x) && std::isfinite(k.pelvis_m.y) &&
           std::isfinite(k.stance.knee_rad) && std::isfinite(k.swing.knee_rad) &&
           std::isfinite(k.stance.hip_rad) && std::isfinite(k.swing.hip_rad);
  }
  return ok;
}

struct Walker {
  FootstepPlanner planner;
  std::vector<double>* times_us;
  TerrainBenchResult* r;
  double configs = 0.0, checks = 0.0;

  // Walks `profile` from s = 0.3 m until the stance passes goal_m; true when it got there.
  bool walk(const GroundProfile& profile, float goal_m) {
    FootstepWindow window;
    window.rear_x_m = window.stance_x_m = 0.3f;
    FootstepPlan plan;
    for (int guard = 0; guard < 200 && window.stance_x_m < goal_m; ++guard) {
      const auto t0 = Clock::now();
      const FootstepStatus status = footstep_plan(planner, profile, window, plan);
      const auto t1 = Clock::now();
      times_us->push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
      ++r->plans;
      configs += plan.configs_evaluated;
      checks += plan.step_checks;
      if (status != FootstepStatus::kOk) {
        ++r->plans_failed;
        ++r->failures[static_cast<size_t>(status)];
        return false;
      }
      if (!plan_finite(plan)) ++r->non_finite;
      if (step_collides(profile, planner.config.walk, plan.steps[0])) ++r->collisions;
      ++r->steps;
      footstep_window_slide(planner, plan, window);
    }
    return window.stance_x_m >= goal_m;
  }
};

// Whole-actor walks: footsteps and upper body, the upper body's planning timed alone.
void run_upper_body_walks(const Scene& scene, const TerrainBenchOptions& options, TerrainBenchResult& r) {
  auto walker = std::make_unique<TerrainWalker>();
  TerrainWalkerConfig config;
  config.footsteps.window_steps = options.window_steps;
  config.footsteps.intervals = options.intervals;
  config.upper_body.max_checks_per_part = options.upper_body_budget;
  if (!terrain_walker_init(*walker, config)) {
    r.error = "invalid upper-body planner config (budget out of range)";
    return;
  }
  SplitMix64 rng{options.seed ^ 0x5eedull};
  std::vector<double> us;
  double checks = 0.0;
  const UpperBodyParams& body = config.upper_body.body;
  for (int i = 0; i < options.upper_body_walks; ++i) {
    GroundPath path;
    float walk_m = 5.0f;
    switch (i % 3) {
      case 0:  // through the low doorway (x 13.8..14.2, z 14.4..15.6, lintel at 1.4 m)
        path = {{rng.uniform(9.5f, 11.5f), 15.0f + rng.uniform(-0.2f, 0.2f)}, radians(90.0f + rng.uniform(-3.0f, 3.0f)), 0.0f};
        break;
      case 1:  // along the shelf (x 15.5..19.7, z 19.1..19.7, 1.1..1.3 m) on the right hand, from before it
        path = {{rng.uniform(14.4f, 15.0f), rng.uniform(18.7f, 18.9f)}, radians(90.0f), 0.0f};
        walk_m = 3.4f;
        break;
      default:  // anywhere, east +-25 degrees
        path = {{rng.uniform(0.8f, 12.0f), rng.uniform(0.8f, 19.2f)}, radians(90.0f + rng.uniform(-25.0f, 25.0f)), 0.0f};
        break;
    }
    if (!terrain_walker_start(*walker, scene, path, walk_m + 5.0f)) continue;
    ++r.upper_body_walks;
    bool stopped = false;
    for (int guard = 0; guard < 40 && terrain_walker_travelled_m(*walker) < walk_m; ++guard) {
      // A wall for the legs ends the walk: not the upper body's failure.
      if (terrain_walker_plan_footsteps(*walker, scene) != TerrainStepStatus::kOk) break;
      const auto t0 = Clock::now();
      const TerrainStepStatus status = terrain_walker_plan_upper_body(*walker);
      us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
      ++r.upper_body_plans;
      for (const UpperBodyPartStats& p : walker->upper_plan.parts) checks += p.checks;
      if (status != TerrainStepStatus::kOk) {
        ++r.upper_body_plans_failed;
        stopped = true;
        break;
      }
      const std::span<const PelvisFrame> track = terrain_walker_track(*walker);
      for (int t = 0; t <= walker->step_frames; ++t) {
        const UpperBodyConfig& c = walker->upper_plan.frames[static_cast<size_t>(t)];
        r.max_waist_flexion_rad = std::max(r.max_waist_flexion_rad, c.waist[0]);
        r.upper_body_collisions += upper_body_clear(body, track[static_cast<size_t>(t)], c, walker->obstacles) ? 0 : 1;
      }
      terrain_walker_commit(*walker);
    }
    r.upper_body_walks_completed += stopped ? 0 : 1;
  }
  r.upper_body_plan_us_p50 = lab::percentile(us, 50.0);
  r.upper_body_plan_us_p99 = lab::percentile(us, 99.0);
  r.upper_body_plan_us_max = us.empty() ? 0.0 : *std::max_element(us.begin(), us.end());
  r.upper_body_checks_per_plan = r.upper_body_plans > 0 ? checks / r.upper_body_plans : 0.0;
  r.collisions += r.upper_body_collisions;
}

}  // namespace

TerrainBenchResult run_terrain_bench(const TerrainBenchOptions& options) {
  TerrainBenchResult r;
  Scene scene;
  if (!scene_load(scene_path(options.scene), scene, r.error)) return r;
  FootstepPlannerConfig config;
  config.window_steps = options.window_steps;
  config.intervals = options.intervals;
  std::vector<double> all_us, scene_us, synthetic_us, cut_us;
  Walker walker{{}, &scene_us, &r};
  if (!footstep_planner_init(walker.planner, config)) {
    r.error = "invalid planner config (window_steps / intervals out of range)";
    return r;
  }

  // Scene paths: start anywhere walkable, heading east +-25 degrees (toward the gap, the hill, the
  // steps and the doorway), curvature up to 1/25 m.
  SplitMix64 rng{options.seed};
  GroundProfile profile;
  const float cut_m = options.walk_m + 4.0f;  // The window and its viability look-ahead.
  for (int accepted = 0, tries = 0; accepted < options.scene_paths && tries < 100 * options.scene_paths; ++tries) {
    const vec2 start{rng.uniform(0.8f, 12.0f), rng.uniform(0.8f, 19.2f)};
    const float heading = radians(90.0f + rng.uniform(-25.0f, 25.0f));
    const GroundPath path{start, heading, rng.uniform(-0.04f, 0.04f)};
    const auto t0 = Clock::now();
    ground_profile_from_scene(scene, path, cut_m, ProfileCutOptions{}, profile);
    cut_us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
    // The start must be a foothold (not astride an edge) for the walk to begin at all.
    Foothold start_foot;
    bool blocked = foothold_fit(profile, walker.planner.config.walk, 0.3f, start_foot) != WalkStatus::kOk;
    for (int i = 0; i < profile.num_samples && !blocked; ++i) {
      const float h = profile.height_m[static_cast<size_t>(i)];
      blocked = std::isnan(h) ? false : h >= scene.terrain.floor_y_m + 0.7f;
    }
    if (blocked) {
      ++r.scene_paths_rejected;
      continue;
    }
    ++accepted;
    ++r.paths;
    r.paths_completed += walker.walk(profile, options.walk_m);
  }
  walker.times_us = &synthetic_us;
  for (int i = 0; i < options.synthetic_profiles; ++i) {
    ground_profile_random(profile, options.seed * 1000003ull + static_cast<std::uint64_t>(i), 14.0f);
    ++r.paths;
    r.paths_completed += walker.walk(profile, 10.0f);
  }

  all_us = scene_us;
  all_us.insert(all_us.end(), synthetic_us.begin(), synthetic_us.end());
  r.footstep_plan_us_p50 = lab::percentile(all_us, 50.0);
  r.footstep_plan_us_p99 = lab::percentile(all_us, 99.0);
  r.footstep_plan_us_max = all_us.empty() ? 0.0 : *std::max_element(all_us.begin(), all_us.end());
  r.scene_plan_us_p50 = lab::percentile(scene_us, 50.0);
  r.synthetic_plan_us_p50 = lab::percentile(synthetic_us, 50.0);
  r.profile_cut_us_p50 = lab::percentile(cut_us, 50.0);
  r.success_rate = r.paths > 0 ? static_cast<double>(r.paths_completed) / r.paths : 0.0;
  r.configs_per_plan = r.plans > 0 ? walker.configs / r.plans : 0.0;
  r.step_checks_per_plan = r.plans > 0 ? walker.checks / r.plans : 0.0;
  run_upper_body_walks(scene, options, r);
  return r;
}

Json to_json(const TerrainBenchResult& r) {
  Json j = {{"footstep_plan_us_p50", rounded(r.footstep_plan_us_p50, 2)},
            {"footstep_plan_us_p99", rounded(r.footstep_plan_us_p99, 2)},
            {"footstep_plan_us_max", rounded(r.footstep_plan_us_max, 2)},
            {"scene_plan_us_p50", rounded(r.scene_plan_us_p50, 2)},
            {"synthetic_plan_us_p50", rounded(r.synthetic_plan_us_p50, 2)},
            {"profile_cut_us_p50", rounded(r.profile_cut_us_p50, 2)},
            {"success_rate", rounded(r.success_rate, 4)},
            {"paths", r.paths},
            {"paths_completed", r.paths_completed},
            {"scene_paths_rejected", r.scene_paths_rejected},
            {"plans", r.plans},
            {"plans_failed", r.plans_failed},
            {"steps", r.steps},
            {"collisions", r.collisions},
            {"non_finite", r.non_finite},
            {"configs_per_plan", rounded(r.configs_per_plan, 2)},
            {"step_checks_per_plan", rounded(r.step_checks_per_plan, 2)}};
  Json& failures = j["failures"] = Json::object();
  for (size_t k = 0; k < r.failures.size(); ++k)
    if (r.failures[k] != 0) failures[std::string(footstep_status_name(static_cast<FootstepStatus>(k)))] = r.failures[k];
  j["upper_body_plan_us_p50"] = rounded(r.upper_body_plan_us_p50, 2);
  j["upper_body_plan_us_p99"] = rounded(r.upper_body_plan_us_p99, 2);
  j["upper_body_plan_us_max"] = rounded(r.upper_body_plan_us_max, 2);
  j["upper_body_plans"] = r.upper_body_plans;
  j["upper_body_plans_failed"] = r.upper_body_plans_failed;
  j["upper_body_walks"] = r.upper_body_walks;
  j["upper_body_walks_completed"] = r.upper_body_walks_completed;
  j["upper_body_collisions"] = r.upper_body_collisions;
  j["upper_body_checks_per_plan"] = rounded(r.upper_body_checks_per_plan, 1);
  j["max_waist_flexion_rad"] = rounded(r.max_waist_flexion_rad, 3);
  if (!r.error.empty()) j["error"] = r.error;
  return j;
}

int bench_terrain(const TerrainBenchCommand& command) {
  print_machine_line();
  const TerrainBenchResult r = run_terrain_bench(command.options);
  if (!r.error.empty()) {
    std::fprintf(stderr, "foresight-bench terrain: %s\n", r.error.c_str());
    return 1;
  }
  std::printf("footsteps (n = %d, m = %d): %d walks, %d completed (%.1f %%), %d plans, %d steps\n",
              command.options.window_steps, command.options.intervals, r.paths, r.paths_completed,
              100.0 * r.success_rate, r.plans, r.steps);
  std::printf("  plan us p50 %.1f p99 %.1f max %.1f; %.1f configurations, %.1f step checks per plan\n",
              r.footstep_plan_us_p50, r.footstep_plan_us_p99, r.footstep_plan_us_max, r.configs_per_plan,
              r.step_checks_per_plan);
  std::printf("upper body: %d walks, %d not stopped by it; %d plans (%d failed)\n", r.upper_body_walks,
              r.upper_body_walks_completed, r.upper_body_plans, r.upper_body_plans_failed);
  std::printf("  plan us p50 %.1f p99 %.1f max %.1f; %.0f collision checks per plan; deepest bend %.2f rad\n",
              r.upper_body_plan_us_p50, r.upper_body_plan_us_p99, r.upper_body_plan_us_max,
              r.upper_body_checks_per_plan, r.max_waist_flexion_rad);
  std::printf("collisions %d (upper body %d), non-finite plans %d\n", r.collisions, r.upper_body_collisions,
              r.non_finite);
  if (command.json) print_json_line(to_json(r));
  return r.collisions == 0 && r.non_finite == 0 ? 0 : 1;
}

}  // namespace foresight::bench

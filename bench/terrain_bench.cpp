#include "terrain_bench.hpp"

#include "terrain/footstep_planner.hpp"
#include "world/data_paths.hpp"
#include "world/scene_load.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

namespace foresight::bench {
namespace {

using namespace foresight::terrain;
using Clock = std::chrono::steady_clock;

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size() - 1) + 0.5));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

// splitmix64: the same paths on every platform (std distributions differ between libraries).
struct Rng {
  std::uint64_t state;
  std::uint64_t next() {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  float uniform(float lo, float hi) {
    return lo + (hi - lo) * static_cast<float>(next() >> 40) * (1.0f / 16777216.0f);
  }
};

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
  Rng rng{options.seed};
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
  r.footstep_plan_us_p50 = percentile(all_us, 0.5);
  r.footstep_plan_us_p99 = percentile(all_us, 0.99);
  r.footstep_plan_us_max = all_us.empty() ? 0.0 : *std::max_element(all_us.begin(), all_us.end());
  r.scene_plan_us_p50 = percentile(scene_us, 0.5);
  r.synthetic_plan_us_p50 = percentile(synthetic_us, 0.5);
  r.profile_cut_us_p50 = percentile(cut_us, 0.5);
  r.success_rate = r.paths > 0 ? static_cast<double>(r.paths_completed) / r.paths : 0.0;
  r.configs_per_plan = r.plans > 0 ? walker.configs / r.plans : 0.0;
  r.step_checks_per_plan = r.plans > 0 ? walker.checks / r.plans : 0.0;
  return r;
}

std::string to_json(const TerrainBenchResult& r) {
  char buf[1024];
  std::snprintf(buf, sizeof buf,
                "{\"footstep_plan_us_p50\":%.2f,\"footstep_plan_us_p99\":%.2f,"
                "\"footstep_plan_us_max\":%.2f,\"scene_plan_us_p50\":%.2f,"
                "\"synthetic_plan_us_p50\":%.2f,\"profile_cut_us_p50\":%.2f,\"success_rate\":%.4f,"
                "\"paths\":%d,\"paths_completed\":%d,\"scene_paths_rejected\":%d,\"plans\":%d,"
                "\"plans_failed\":%d,\"steps\":%d,\"collisions\":%d,\"non_finite\":%d,"
                "\"configs_per_plan\":%.2f,\"step_checks_per_plan\":%.2f",
                r.footstep_plan_us_p50, r.footstep_plan_us_p99, r.footstep_plan_us_max,
                r.scene_plan_us_p50, r.synthetic_plan_us_p50, r.profile_cut_us_p50, r.success_rate,
                r.paths, r.paths_completed, r.scene_paths_rejected, r.plans, r.plans_failed,
                r.steps, r.collisions, r.non_finite, r.configs_per_plan, r.step_checks_per_plan);
  std::string out = buf;
  out += ",\"failures\":{";
  bool first = true;
  for (size_t k = 0; k < r.failures.size(); ++k) {
    if (r.failures[k] == 0) continue;
    out += first ? "" : ",";
    first = false;
    out += "\"";
    out += footstep_status_name(static_cast<FootstepStatus>(k));
    out += "\":" + std::to_string(r.failures[k]);
  }
  out += "}";
  if (!r.error.empty()) out += ",\"error\":\"" + r.error + "\"";
  out += "}";
  return out;
}

}  // namespace foresight::bench

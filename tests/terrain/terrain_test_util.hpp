#pragma once
// Helpers shared by the terrain tests: walking a profile with the planner (or a fixed step) and
// checking the motion against the ground.
#include "terrain/footstep_planner.hpp"

#include <cmath>
#include <vector>

namespace foresight::terrain::test {

/// 40 m of flat floor at y = 0 (centred on the origin), with `boxes` in it.
inline Scene flat_scene(std::vector<SceneBox> boxes = {}) {
  Scene scene;
  scene.name = "flat";
  scene.bounds = {{-20.0f, -20.0f}, {20.0f, 20.0f}};
  scene.boxes = std::move(boxes);
  return scene;
}

/// What a walk along a profile did.
struct WalkLog {
  FootstepStatus last_status = FootstepStatus::kOk;  ///< kOk when the walk reached its goal.
  std::vector<WalkStep> steps;                       ///< Executed steps (first step of each plan).
  std::vector<FootstepPlan> plans;
  bool non_finite = false;                           ///< Any NaN/inf in a successful plan.
};

inline bool finite_step(const WalkStep& s) {
  bool ok = std::isfinite(s.lift_m);
  for (const WalkKeyFrame& k : s.keys)
    ok = ok && std::isfinite(k.pelvis_m.x) && std::isfinite(k.pelvis_m.y) &&
         std::isfinite(k.stance.hip_rad) && std::isfinite(k.stance.knee_rad) &&
         std::isfinite(k.stance.ankle_rad) && std::isfinite(k.swing.hip_rad) &&
         std::isfinite(k.swing.knee_rad) && std::isfinite(k.swing.ankle_rad);
  for (const vec2& p : s.swing_ankle_bezier_m) ok = ok && std::isfinite(p.x) && std::isfinite(p.y);
  return ok;
}

/// Plans and slides from feet together at start_m until the stance passes goal_m or planning fails.
inline WalkLog walk_with_planner(FootstepPlanner& planner, const GroundProfile& profile,
                                 float start_m, float goal_m, int max_steps = 200) {
  WalkLog log;
  FootstepWindow window;
  window.rear_x_m = window.stance_x_m = start_m;
  for (int i = 0; i < max_steps && window.stance_x_m < goal_m; ++i) {
    FootstepPlan plan;
    log.last_status = footstep_plan(planner, profile, window, plan);
    if (log.last_status != FootstepStatus::kOk) return log;
    for (int k = 0; k < plan.num_steps; ++k) {
      log.non_finite = log.non_finite || !finite_step(plan.steps[static_cast<std::size_t>(k)]) ||
                       !std::isfinite(plan.footholds[static_cast<std::size_t>(k)].sole_y_m) ||
                       !std::isfinite(plan.cost);
    }
    log.plans.push_back(plan);
    log.steps.push_back(plan.steps[0]);
    footstep_window_slide(planner, plan, window);
  }
  return log;
}

/// Ground height under x (NaN over a gap or outside).
inline float ground_at(const GroundProfile& profile, float x) {
  float h = NAN;
  return profile.height_at(x, h) ? h : NAN;
}

/// Largest depth (m) by which a sampled swing sole point (heel, ankle sole, toe) goes below the
/// profile over the step, at `samples` phases. 0 when never below.
inline float swing_penetration_m(const GroundProfile& profile, const WalkParams& params,
                                 const WalkStep& step, int samples = 64) {
  float worst = 0.0f;
  for (int k = 0; k <= samples; ++k) {
    WalkFrame f;
    walk_step_sample(step, params, static_cast<float>(k) / static_cast<float>(samples), f);
    const vec2 sole = f.swing_ankle_m - vec2(0.0f, params.ankle_height_m);
    for (const vec2 p : {f.swing_heel_m, sole, f.swing_toe_m}) {
      const float g = ground_at(profile, p.x);
      if (std::isnan(g)) continue;  // Over a gap: nothing to go through.
      worst = std::max(worst, g - p.y);
    }
  }
  return worst;
}

/// True when any cell under the planted foot is a gap.
inline bool foot_in_gap(const GroundProfile& profile, const WalkParams& params, float ankle_x) {
  for (float x = ankle_x - params.heel_back_m; x <= ankle_x + params.toe_front_m; x += 0.01f)
    if (std::isnan(ground_at(profile, x))) return true;
  return false;
}

}  // namespace foresight::terrain::test

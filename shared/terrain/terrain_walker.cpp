#include "terrain/terrain_walker.hpp"

#include <algorithm>

namespace foresight::terrain {

const char* terrain_step_status_name(TerrainStepStatus status) {
  switch (status) {
    case TerrainStepStatus::kOk: return "ok";
    case TerrainStepStatus::kFootstepsFailed: return "footsteps failed";
    case TerrainStepStatus::kUpperBodyFailed: return "upper body failed";
    case TerrainStepStatus::kNotStarted: return "not started";
  }
  return "?";
}

bool terrain_walker_init(TerrainWalker& walker, const TerrainWalkerConfig& config) {
  walker.config = config;
  walker.started = false;
  return config.speed_mps > 0.0f && config.dt_s > 0.0f && footstep_planner_init(walker.footsteps, config.footsteps) &&
         upper_body_planner_init(walker.upper_body, config.upper_body);
}

bool terrain_walker_start(TerrainWalker& walker, const Scene& scene, const GroundPath& path, float length_m,
                          float start_x_m) {
  walker.started = false;
  if (!ground_profile_from_scene(scene, path, length_m, ProfileCutOptions{}, walker.profile)) return false;
  walker.window = FootstepWindow{};
  walker.window.rear_x_m = walker.window.stance_x_m = start_x_m;
  walker.swing_left = true;
  walker.fresh = true;
  walker.guide_frames = 0;
  walker.started = true;
  return true;
}

bool terrain_walker_recut(TerrainWalker& walker, const Scene& scene, const GroundPath& path, float length_m,
                          float rear_x_m, float stance_x_m) {
  walker.started = ground_profile_from_scene(scene, path, length_m, ProfileCutOptions{}, walker.profile);
  walker.window.rear_x_m = rear_x_m;
  walker.window.stance_x_m = stance_x_m;
  return walker.started;
}

TerrainStepStatus terrain_walker_plan_footsteps(TerrainWalker& walker, const Scene& scene) {
  if (!walker.started) return TerrainStepStatus::kNotStarted;
  const TerrainWalkerConfig& c = walker.config;
  if (footstep_plan(walker.footsteps, walker.profile, walker.window, walker.plan) != FootstepStatus::kOk)
    return TerrainStepStatus::kFootstepsFailed;
  walker.track_frames = pelvis_track_from_plan(walker.plan, c.footsteps.walk, walker.profile.path, c.speed_mps,
                                               c.dt_s, walker.swing_left, walker.track, walker.step_frames);
  gather_upper_body_obstacles(scene, terrain_walker_track(walker), c.obstacle_reach_m, c.upper_obstacle_min_top_m,
                              walker.obstacles);
  if (walker.fresh) walker.upper = upper_body_pattern_config(c.upper_body.body, walker.track[0]);
  return TerrainStepStatus::kOk;
}

TerrainStepStatus terrain_walker_plan_upper_body(TerrainWalker& walker) {
  return upper_body_plan(walker.upper_body, terrain_walker_track(walker), walker.config.dt_s, walker.obstacles,
                         walker.upper, walker.upper_plan,
                         std::span<const UpperBodyConfig>(walker.guide.data(), static_cast<size_t>(walker.guide_frames))) ==
                 UpperBodyStatus::kOk
             ? TerrainStepStatus::kOk
             : TerrainStepStatus::kUpperBodyFailed;
}

void terrain_walker_commit(TerrainWalker& walker) {
  footstep_window_slide(walker.footsteps, walker.plan, walker.window);
  walker.upper = walker.upper_plan.frames[static_cast<size_t>(walker.step_frames)];
  walker.guide_frames = walker.upper_plan.num_frames - walker.step_frames;
  std::copy_n(walker.upper_plan.frames.begin() + walker.step_frames, walker.guide_frames, walker.guide.begin());
  walker.swing_left = !walker.swing_left;
  walker.fresh = false;
}

TerrainStepStatus terrain_walker_step(TerrainWalker& walker, const Scene& scene) {
  TerrainStepStatus status = terrain_walker_plan_footsteps(walker, scene);
  if (status == TerrainStepStatus::kOk) status = terrain_walker_plan_upper_body(walker);
  if (status == TerrainStepStatus::kOk) terrain_walker_commit(walker);
  return status;
}

}  // namespace foresight::terrain

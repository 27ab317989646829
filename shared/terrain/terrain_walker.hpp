#pragma once
// A terrain actor walking a path, one step at a time, as the decoupled footstep paper runs it
// (Fig. 2): the footstep planner plans the window of the next n steps on the ground profile, the
// upper-body planner plans waist and arms along that window's pelvis trajectory, and only the
// first step is committed (both planners start the next step from where this one ends). When
// either planner fails the actor does not move (paper 3.2: the player steers away).
#include "terrain/footstep_planner.hpp"
#include "terrain/upper_body_planner.hpp"

namespace foresight::terrain {

struct TerrainWalkerConfig {
  FootstepPlannerConfig footsteps;
  UpperBodyPlannerConfig upper_body;
  float speed_mps = 1.2f;      ///< Walking speed: a step lasts its pelvis advance / speed.
  float dt_s = 1.0f / 30.0f;   ///< Animation frame (the server's tick).
  float obstacle_reach_m = 1.2f;  ///< Boxes this far from the pelvis path are gathered for the upper body.
  float upper_obstacle_min_top_m = 0.5f;  ///< Boxes topping out lower are the legs' (the profile).
};

enum class TerrainStepStatus : std::uint8_t { kOk, kFootstepsFailed, kUpperBodyFailed, kNotStarted };
const char* terrain_step_status_name(TerrainStepStatus status);

/// Fixed workspace; terrain_walker_init is its only allocation.
struct TerrainWalker {
  TerrainWalkerConfig config;
  FootstepPlanner footsteps;
  UpperBodyPlanner upper_body;
  GroundProfile profile;
  FootstepWindow window;
  UpperBodyConfig upper;  ///< Shown now (the end of the last committed step).
  bool swing_left = true;  ///< The leg that swings in the next step.
  bool started = false;
  bool fresh = true;  ///< No step taken yet: the upper body starts in its pattern.
  // The last call's plans; on kOk, frames [0, step_frames] of track/upper_plan are the committed step.
  FootstepPlan plan;
  UpperBodyPlan upper_plan;
  UpperBodyObstacles obstacles;
  std::array<PelvisFrame, kMaxUpperBodyFrames> track{};
  /// The committed plan's frames after the committed step: the next plan's guide.
  std::array<UpperBodyConfig, kMaxUpperBodyFrames> guide{};
  int guide_frames = 0;
  int track_frames = 0;
  int step_frames = 0;
};

bool terrain_walker_init(TerrainWalker& walker, const TerrainWalkerConfig& config);
/// Cuts the scene along `path` for `length_m` and stands the actor at the path's start (feet
/// together `start_x_m` along it; the first step starts the upper body in its pattern). False
/// when the cut is empty.
bool terrain_walker_start(TerrainWalker& walker, const Scene& scene, const GroundPath& path, float length_m,
                          float start_x_m = 0.3f);
/// Cuts the scene along `path` (a steered continuation of the walked path: ground_path_steer) and
/// puts the window's feet on it at rear_x_m and stance_x_m; the rest of the walk (the leg that
/// swings next, the upper body and its guide, the footstep seed) carries on. False when the cut
/// is empty (the walker is then not started).
bool terrain_walker_recut(TerrainWalker& walker, const Scene& scene, const GroundPath& path, float length_m,
                          float rear_x_m, float stance_x_m);
/// Plans and commits one step: plan_footsteps, plan_upper_body, commit. kOk: the window slid,
/// `upper` is the step's last frame; otherwise nothing moved.
TerrainStepStatus terrain_walker_step(TerrainWalker& walker, const Scene& scene);
// The stages of terrain_walker_step, for callers that time them apart (the benchmark).
/// The footstep window, its pelvis track and the boxes near it; kOk or kFootstepsFailed.
TerrainStepStatus terrain_walker_plan_footsteps(TerrainWalker& walker, const Scene& scene);
/// The upper body along the track from `upper`; kOk or kUpperBodyFailed.
TerrainStepStatus terrain_walker_plan_upper_body(TerrainWalker& walker);
/// Commits the planned first step (both plans kOk).
void terrain_walker_commit(TerrainWalker& walker);
/// The last planned window's pelvis track.
inline std::span<const PelvisFrame> terrain_walker_track(const TerrainWalker& walker) {
  return {walker.track.data(), static_cast<size_t>(walker.track_frames)};
}
/// The stance ankle's distance along the path.
inline float terrain_walker_travelled_m(const TerrainWalker& walker) { return walker.window.stance_x_m; }

}  // namespace foresight::terrain

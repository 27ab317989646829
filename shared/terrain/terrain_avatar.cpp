#include "terrain/terrain_avatar.hpp"

#include "world/terrain.hpp"

#include <algorithm>
#include <cmath>

namespace foresight::terrain {

namespace {

vec2 forward(float heading_rad) { return {std::sin(heading_rad), std::cos(heading_rad)}; }

// Does the planned step bring the pelvis closer than personal_space_m to another avatar (now or
// where its own step ends), and closer than it already is? Moving away is always allowed, so two
// avatars that came too close can still part.
bool step_vetoed(const TerrainAvatar& a, std::span<const TerrainNeighbour> others) {
  const auto track = terrain_walker_track(a.walker);
  const float space = a.config.personal_space_m;
  for (const TerrainNeighbour& o : others) {
    for (vec2 p : {o.now_m, o.step_end_m}) {
      const float start = glm::length(ground(track[0].pos_m) - p);
      for (int f = 1; f <= a.walker.step_frames; ++f) {
        const float d = glm::length(ground(track[static_cast<size_t>(f)].pos_m) - p);
        if (d < space && d < start - 1e-3f) return true;
      }
    }
  }
  return false;
}

void refuse(TerrainAvatar& a) {
  ++a.refusals;
  a.wait_frames = a.config.retry_frames;
}

// Re-cuts the walker's profile for the next window toward `want_heading` (see the header).
bool recut_toward(TerrainAvatar& a, const Scene& scene, float want_heading) {
  TerrainWalker& w = a.walker;
  const TerrainAvatarConfig& c = a.config;
  const GroundPath walked = w.profile.path;
  const float rear = w.window.rear_x_m, stance = w.window.stance_x_m;
  const float stride = stance - rear;
  if (stride < 1e-3f) {
    // Feet together (standing at the spawn): turn on the spot to the wanted heading.
    const vec2 at = ground_path_point(walked, stance);
    const GroundPath path{at - c.lead_m * forward(want_heading), want_heading, 0.0f};
    return terrain_walker_recut(w, scene, path, c.lead_m + c.look_ahead_m, c.lead_m, c.lead_m);
  }
  const float turn = std::clamp(wrap_angle(want_heading - ground_path_heading(walked, stance)),
                                -c.max_turn_per_step_rad, c.max_turn_per_step_rad);
  const GroundPath path =
      ground_path_steer(walked, rear, stance, c.lead_m, turn, c.walker.footsteps.step_neutral_m);
  return terrain_walker_recut(w, scene, path, c.lead_m + stride + c.look_ahead_m, c.lead_m, c.lead_m + stride);
}

void try_step(TerrainAvatar& a, const Scene& scene, vec2 direction, std::span<const TerrainNeighbour> others) {
  TerrainWalker& w = a.walker;
  a.vetoed = false;
  TerrainStepStatus status = recut_toward(a, scene, heading_of(direction)) ? terrain_walker_plan_footsteps(w, scene)
                                                                          : TerrainStepStatus::kFootstepsFailed;
  if (status == TerrainStepStatus::kOk) status = terrain_walker_plan_upper_body(w);
  a.last_status = status;
  if (status == TerrainStepStatus::kOk && step_vetoed(a, others)) a.vetoed = true;
  if (status != TerrainStepStatus::kOk || a.vetoed) return refuse(a);
  a.step = w.plan.steps[0];
  a.step_path = w.profile.path;
  a.step_swing_left = w.swing_left;
  a.step_frames = w.step_frames;
  std::copy_n(w.upper_plan.frames.begin(), a.step_frames + 1, a.step_upper.begin());
  a.step_end_m = ground(w.track[static_cast<size_t>(a.step_frames)].pos_m);
  terrain_walker_commit(w);
  a.frame = 0;
  a.stepping = true;
  ++a.steps;
}

// Turns on the spot to face want_heading, feet together under the pelvis (see the header).
void start_pivot(TerrainAvatar& a, const Scene& scene, float want_heading) {
  const TerrainAvatarConfig& c = a.config;
  const vec2 at = terrain_avatar_ground(a);
  float ground_y = 0.0f;
  if (!terrain_height_at(scene.terrain, at, ground_y)) return refuse(a);
  const TerrainBodyPose to =
      terrain_body_standing(c.walker.footsteps.walk, c.walker.upper_body.body, at, ground_y, want_heading);
  const PelvisFrame frame{to.pelvis_m, want_heading, 0.0f, 0.0f};
  TerrainWalker& w = a.walker;
  gather_upper_body_obstacles(scene, std::span(&frame, 1), c.walker.obstacle_reach_m, c.walker.upper_obstacle_min_top_m,
                              w.obstacles);
  if (w.obstacles.overflow || !upper_body_clear(c.walker.upper_body.body, frame, to.upper, w.obstacles)) return refuse(a);
  const GroundPath path{at - c.lead_m * forward(want_heading), want_heading, 0.0f};
  if (!terrain_walker_start(w, scene, path, c.lead_m + c.look_ahead_m, c.lead_m)) return refuse(a);
  a.pivot_from = a.body;
  a.pivot_to = to;
  const float turn = std::abs(wrap_angle(want_heading - a.body.heading_rad));
  a.pivot_frames = std::max(4, static_cast<int>(std::ceil(turn / (c.pivot_speed_radps * c.walker.dt_s))));
  a.pivot_frame = 0;
  a.pivoting = true;
  ++a.pivots;
}

}  // namespace

bool terrain_avatar_init(TerrainAvatar& a, const TerrainAvatarConfig& c, const Scene& scene, vec2 ground_m,
                         float heading_rad) {
  a.config = c;
  a.stepping = false;
  a.wait_frames = 0;
  a.steps = a.refusals = 0;
  a.pivoting = false;
  if (!terrain_walker_init(a.walker, c.walker) || !(c.lead_m > 0.1f) || !(c.look_ahead_m > 0.0f) ||
      !(c.max_turn_per_step_rad >= 0.0f) || !(c.pivot_speed_radps > 0.0f))
    return false;
  const GroundPath path{ground_m - c.lead_m * forward(heading_rad), heading_rad, 0.0f};
  float ground_y = 0.0f;
  if (!terrain_walker_start(a.walker, scene, path, c.lead_m + c.look_ahead_m, c.lead_m) ||
      !a.walker.profile.height_at(c.lead_m, ground_y))
    return false;
  a.body = terrain_body_standing(c.walker.footsteps.walk, c.walker.upper_body.body, ground_m, ground_y, heading_rad);
  a.step_end_m = ground_m;
  return true;
}

bool terrain_avatar_frame(TerrainAvatar& a, const Scene& scene, vec2 direction,
                          std::span<const TerrainNeighbour> others) {
  // A step that ends this frame chains into the next one without a standing frame.
  bool step_ended = false;
  if (a.stepping) {
    ++a.frame;
    a.body = terrain_body_at(a.step, a.config.walker.footsteps.walk, a.step_path,
                             static_cast<float>(a.frame) / static_cast<float>(a.step_frames), a.step_swing_left,
                             a.step_upper[static_cast<size_t>(a.frame)]);
    step_ended = a.frame >= a.step_frames;
    a.stepping = !step_ended;
  } else if (a.pivoting) {
    ++a.pivot_frame;
    a.body = terrain_body_lerp(a.pivot_from, a.pivot_to,
                               static_cast<float>(a.pivot_frame) / static_cast<float>(a.pivot_frames));
    a.pivoting = a.pivot_frame < a.pivot_frames;
  }
  if (a.stepping || a.pivoting) return false;
  a.step_end_m = terrain_avatar_ground(a);
  if (a.wait_frames > 0) {
    --a.wait_frames;
    return false;
  }
  const bool moving = std::isfinite(direction.x) && std::isfinite(direction.y) && glm::dot(direction, direction) > 1e-6f;
  if (!moving) return false;
  const float want = heading_of(direction);
  // Walking on, a step turns toward the direction; standing, a larger turn is made on the spot.
  if (!step_ended && std::abs(wrap_angle(want - a.body.heading_rad)) > a.config.pivot_threshold_rad)
    start_pivot(a, scene, want);
  else
    try_step(a, scene, direction, others);
  return true;
}

}  // namespace foresight::terrain

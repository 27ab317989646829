#include "library/pose_check.hpp"

#include "anim/fk.hpp"
#include "world/collision_check.hpp"
#include "world/terrain.hpp"

#include <algorithm>
#include <cctype>

namespace foresight {

float head_top_margin_m(const Skeleton& skeleton) {
  for (int j = 1; j < skeleton.num_joints(); ++j) {
    if (!skeleton.is_end_site[j]) continue;
    std::string parent = skeleton.joint_names[skeleton.parents[j]];
    for (char& c : parent) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (parent.find("head") != std::string::npos && glm::length(skeleton.rest_offsets_m[j]) >= 0.05f)
      return 0.03f;
  }
  return 0.15f;
}

bool shown_pose_collides(const MotionLibrary& library, const CollisionWorld& world,
                         const PlaybackState& state, PoseCheckScratch& scratch, float tolerance_m) {
  playback_pose(library, state, scratch.pose);
  scratch.joint_pos_m.resize(static_cast<size_t>(library.num_joints()));
  scratch.joint_rot.resize(static_cast<size_t>(library.num_joints()));
  fk_pose(library.skeleton, scratch.pose.local_pos_m, scratch.pose.local_rot, scratch.joint_pos_m,
          scratch.joint_rot);
  const Placement to_local = state.segment_start.inverse();
  for (vec3& p : scratch.joint_pos_m) p = to_local.apply(p);
  const float flesh_m = std::max(library.body_margin_m - tolerance_m, 0.0f);
  const float facing = playback_root(library, state).heading_rad - state.segment_start.heading_rad;
  BodyVolume body = place(body_volume_from_pose(scratch.joint_pos_m, vec2(std::sin(facing), std::cos(facing)),
                                                flesh_m, library.head_top_margin_m),
                          state.segment_start);
  float ground_m = 0.0f;
  ground_height_at(world, state.segment_start.pos_m, ground_m);
  body.y_min_m += ground_m;
  body.y_max_m += ground_m;
  // Bounds and the terrain rule at the body's centre, as the tree checks them.
  if (frame_collides(world, BodyVolume{body.center_m, 0.0f, body.y_min_m, body.y_max_m}, ground_m)) return true;
  // The flesh itself: every joint grown by the margin, over the body's heights. Every precomputed
  // capsule holds these discs, whatever angle it was fitted at.
  for (const vec3& p : scratch.joint_pos_m) {
    const vec2 at = state.segment_start.apply(ground(p));
    if (volume_hits_boxes(world, BodyVolume{at, flesh_m, body.y_min_m, body.y_max_m})) return true;
  }
  return false;
}

BodyHeights body_heights(const MotionLibrary& library, std::span<const vec3> joints_world_m) {
  if (joints_world_m.empty()) return {};
  float low = joints_world_m[0].y, high = joints_world_m[0].y;
  for (const vec3& p : joints_world_m) low = std::min(low, p.y), high = std::max(high, p.y);
  // As body_volume_from_pose takes them.
  return {low, high + library.head_top_margin_m};
}

bool joint_flesh_collides(const MotionLibrary& library, const CollisionWorld& world, vec3 joint_world_m,
                          BodyHeights heights, float tolerance_m) {
  const float flesh_m = std::max(library.body_margin_m - tolerance_m, 0.0f);
  return volume_hits_boxes(world, BodyVolume{ground(joint_world_m), flesh_m, heights.y_min_m, heights.y_max_m});
}

bool shown_joints_collide(const MotionLibrary& library, const CollisionWorld& world,
                          std::span<const vec3> joints_world_m, float tolerance_m) {
  const BodyHeights heights = body_heights(library, joints_world_m);
  for (const vec3& p : joints_world_m)
    if (joint_flesh_collides(library, world, p, heights, tolerance_m)) return true;
  return false;
}

}  // namespace foresight

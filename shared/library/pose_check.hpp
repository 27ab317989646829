#pragma once
// The collision check of the pose actually shown (FK of the played, blended pose), independent of
// the precomputed segment volumes the tree trusts: what replays, demos and tests use to prove that
// an avatar never overlaps the scene.
#include "library/playback.hpp"
#include "world/collision_world.hpp"

#include <span>
#include <vector>

namespace foresight {

/// How far above its highest joint the body reaches: little when the skeleton ends in a head-top
/// End Site (the default library), a head's height when the head joint is its top (e.g. the
/// Bandai captures, whose head End Site has a zero offset).
float head_top_margin_m(const Skeleton& skeleton);

/// Reusable buffers, so checking every frame allocates nothing.
struct PoseCheckScratch {
  Pose pose;
  std::vector<vec3> joint_pos_m;
  std::vector<quat> joint_rot;
};

/// True when the shown pose of `state` overlaps the scene: any joint grown by the library's flesh
/// margin, over the body's height range, overlaps a box, or the body's centre (the capsule the
/// library fits, in the segment's own frame) breaks the bounds or the terrain rule. The clip
/// plays at the ground height under its segment's start. `tolerance_m` shrinks the flesh: an
/// observer that rebuilds the pose from quantised snapshots (1 mm) passes 1 cm, so a body that
/// grazes a wall on the server is not counted as inside it.
bool shown_pose_collides(const MotionLibrary& library, const CollisionWorld& world,
                         const PlaybackState& state, PoseCheckScratch& scratch, float tolerance_m = 0.0f);

/// The flesh test of shown_pose_collides for world joint positions (a pose after the pose stage):
/// any joint grown by the library's flesh margin, over the body's height range, overlaps a box.
bool shown_joints_collide(const MotionLibrary& library, const CollisionWorld& world,
                          std::span<const vec3> joints_world_m, float tolerance_m = 0.0f);

/// The body's height range shown_joints_collide grows each joint over: its lowest joint to the
/// head top.
struct BodyHeights {
  float y_min_m = 0.0f, y_max_m = 0.0f;
};
BodyHeights body_heights(const MotionLibrary& library, std::span<const vec3> joints_world_m);
/// One joint's part of shown_joints_collide: its flesh disc over `heights` overlaps a box (or
/// leaves the bounds).
bool joint_flesh_collides(const MotionLibrary& library, const CollisionWorld& world, vec3 joint_world_m,
                          BodyHeights heights, float tolerance_m = 0.0f);

}  // namespace foresight

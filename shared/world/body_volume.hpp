#pragma once
// The avatar's body for collision, one volume per frame: a capsule on the ground plane (a core
// segment along the body's facing, grown by a radius) swept between two heights. Along the facing,
// so a striding walker is as narrow as a person across its path (about 0.6 m with its flesh
// margin: a 0.8 m gap passes) rather than a disc as wide as its stride (1.05 m); height-aware, so
// a crouching avatar (lower y_max_m) fits under a table that a walking one hits. A zero half axis
// is a disc (vertical cylinder). Computed offline from the pose; the tick only transforms it.
#include "math/types.hpp"

#include <span>

namespace foresight {

struct BodyVolume {
  vec2 center_m{0.0f};  ///< Centre of the core segment on the ground plane (x, z).
  float radius_m = 0.0f;
  float y_min_m = 0.0f;  ///< Lowest point of the body (feet), metres.
  float y_max_m = 0.0f;  ///< Highest point (top of the head), metres.
  /// From the centre to one end of the core segment (the other end is centre - half_axis);
  /// zero for a disc.
  vec2 half_axis_m{0.0f};

  /// Radius of the disc about center_m that holds the whole footprint.
  float reach_m() const { return glm::length(half_axis_m) + radius_m; }
};

/// The capsule along `facing` (the character's forward on the ground; need not be unit length)
/// holding one pose's joint positions, grown by `margin_m` sideways and `head_top_m` above the
/// highest joint (joints are bone ends; flesh extends past them). Along the facing, because a
/// body passes a door or a corridor facing along it: its radius is then half the body's width
/// across its path, the figure that decides what it fits through.
BodyVolume body_volume_from_pose(std::span<const vec3> joint_pos_m, vec2 facing, float margin_m = 0.08f,
                                 float head_top_m = 0.12f);

/// The volume moved by a ground placement.
inline BodyVolume place(const BodyVolume& v, const Placement& p) {
  return {p.apply(v.center_m), v.radius_m, v.y_min_m, v.y_max_m, rotate_ground(v.half_axis_m, p.heading_rad)};
}

/// Squared distance between segments p0-p1 and q0-q1 (0 when they cross).
float segment_distance_sq(vec2 p0, vec2 p1, vec2 q0, vec2 q1);

/// Do two footprints come closer than `clearance_m` (heights ignored)? Touching is not overlapping.
inline bool footprints_overlap(const BodyVolume& a, const BodyVolume& b, float clearance_m = 0.0f) {
  const float r = a.radius_m + b.radius_m + clearance_m;
  return segment_distance_sq(a.center_m - a.half_axis_m, a.center_m + a.half_axis_m,
                             b.center_m - b.half_axis_m, b.center_m + b.half_axis_m) < r * r;
}

/// Do the ground footprints of any two bodies overlap (heights ignored)? Sorts `bodies` by x and
/// sweeps, so only bodies whose x ranges overlap are compared: O(n log n) for spread bodies.
bool any_footprints_overlap(std::span<BodyVolume> bodies);

}  // namespace foresight

#pragma once
// The avatar's body for collision, one volume per frame: a vertical cylinder (a disc on the ground
// plane swept between two heights). Height-aware, so a crouching avatar (lower y_max_m) fits under
// a table that a walking one hits. Computed offline from the pose; the tick only transforms it.
#include "math/types.hpp"

#include <span>

namespace foresight {

struct BodyVolume {
  vec2 center_m{0.0f};  ///< Disc centre on the ground plane (x, z), in the space of the pose.
  float radius_m = 0.0f;
  float y_min_m = 0.0f;  ///< Lowest point of the body (feet), metres.
  float y_max_m = 0.0f;  ///< Highest point (top of the head), metres.
};

/// Bounding cylinder of one pose's joint positions, grown by `margin_m` sideways and
/// `head_top_m` above the highest joint (joints are bone ends; flesh extends past them).
BodyVolume body_volume_from_pose(std::span<const vec3> joint_pos_m, float margin_m = 0.08f,
                                 float head_top_m = 0.12f);

/// The smallest volume holding both: the disc enclosing both discs, both height ranges.
BodyVolume enclosing_volume(const BodyVolume& a, const BodyVolume& b);

/// The volume moved by a ground placement (rotation about the disc's centre does not change a disc).
inline BodyVolume place(const BodyVolume& v, const Placement& p) {
  return {p.apply(v.center_m), v.radius_m, v.y_min_m, v.y_max_m};
}

/// Do the ground discs of any two bodies overlap (heights ignored)? Sorts `bodies` by x and
/// sweeps, so only bodies whose x ranges overlap are compared: O(n log n) for spread bodies.
bool any_discs_overlap(std::span<BodyVolume> bodies);

}  // namespace foresight

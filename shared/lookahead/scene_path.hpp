#pragma once
// A coarse route planner: where a walker of a given clearance and height can go, as a few straight
// legs. The scripted player plans with it, NPC fighters route around walls with it, and the avatar
// controller probes a turn's way with scene_segment_clear; the feasible motion tree does its own,
// exact, collision checks.
//
// Model: a point is free when a standing (or crouching) body there, a vertical cylinder of radius
// clearance_m from the ground up to body_height_m above it, passes frame_collides() with the
// ground under the point as reference (the world's terrain rule). Neighbouring points are
// connected when both are free, their midpoint is free and their ground heights differ by at most
// the world's ground tolerance.
#include "library/motion_library.hpp"
#include "math/types.hpp"
#include "world/collision_world.hpp"

#include <vector>

namespace foresight {

inline constexpr float kRouteGridSpacing_m = 0.25f;

/// True when every point of the straight segment a-b (sampled every <= 0.1 m) is free as above
/// and the ground along it has no step larger than the tolerance.
bool scene_segment_clear(const CollisionWorld& world, vec2 a, vec2 b, float clearance_m,
                         float body_height_m);

/// A* over a grid of points 0.25 m apart (aligned to multiples of 0.25 m; coarser for scenes
/// over ~500 m a side), 8-connected without cutting corners, from `from` to `to`, then
/// string-pulled: each leg is the longest straight segment that scene_segment_clear accepts.
/// `from` and `to` are joined to their nearest free grid points (within max(clearance, 0.5 m),
/// by a clear thin segment). On success `waypoints` = [from, corner, ..., to] (at least two
/// points); false (waypoints emptied) when there is no route or an argument is not finite.
/// Deterministic.
bool scene_route(const CollisionWorld& world, vec2 from, vec2 to, float clearance_m,
                 float body_height_m, std::vector<vec2>& waypoints);

/// scene_route for a standing walker (body height 1.85 m).
inline bool scene_route(const CollisionWorld& world, vec2 from, vec2 to, float clearance_m,
                        std::vector<vec2>& waypoints) {
  return scene_route(world, from, to, clearance_m, kStandingHeight_m, waypoints);
}

/// Sum of the legs' lengths.
float route_length_m(const std::vector<vec2>& waypoints);

}  // namespace foresight

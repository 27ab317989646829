#include "library/body_fit.hpp"

#include "world/collision_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace foresight {
namespace {

/// Distance from the placed frame's core segment to a box's ground rectangle: 0 when an end lies
/// in it, else the nearest of its four edges (segment_distance_sq).
float core_to_rect_m(const BodyVolume& v, const SceneBox& b) {
  const vec2 p0 = v.center_m - v.half_axis_m, p1 = v.center_m + v.half_axis_m;
  const GroundRect r = b.ground_rect();
  if (r.contains(p0) || r.contains(p1)) return 0.0f;
  const vec2 c[4] = {r.min_m, {r.max_m.x, r.min_m.y}, r.max_m, {r.min_m.x, r.max_m.y}};
  float d2 = std::numeric_limits<float>::max();
  for (int i = 0; i < 4; ++i) d2 = std::min(d2, segment_distance_sq(p0, p1, c[i], c[(i + 1) % 4]));
  return std::sqrt(d2);
}

std::string metres(float v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f m", static_cast<double>(v));
  return buf;
}

}  // namespace

std::string body_fit_problem(const MotionLibrary& library, const Scene& scene, const CollisionWorld& world,
                             int segment, const Placement& at) {
  if (segment < 0 || segment >= library.graph.num_segments()) return "no such segment";
  const SegmentCollisionShape& shape = library.segment_shapes[static_cast<size_t>(segment)];
  if (segment_feasible(world, shape, at)) return {};
  const std::string body = "the " + library.graph.segments[static_cast<size_t>(segment)].name + " body (" +
                           metres(segment_body(library, segment).width_m) + " across)";
  float h0 = 0.0f;
  if (!scene.bounds.contains(at.pos_m) || !ground_height_at(world, at.pos_m, h0))
    return body + " has no ground under it (outside the scene or over a hole)";
  // The frame that collides first, and the box it overlaps most.
  const int first = std::max(segment_first_collision(world, shape, at), 0);
  BodyVolume v = place(shape.frames[static_cast<size_t>(first)], at);
  v.y_min_m += h0;
  v.y_max_m += h0;
  const SceneBox* worst = nullptr;
  float depth = 0.0f;
  for (const SceneBox& b : scene.boxes) {
    if (!y_ranges_overlap(v.y_min_m, v.y_max_m, b.min_m.y, b.max_m.y)) continue;
    const float d = v.radius_m - core_to_rect_m(v, b);
    if (d > depth) depth = d, worst = &b;
  }
  if (worst == nullptr)
    return body + " leaves the scene's bounds or stands on ground more than " +
           metres(world.config.ground_tolerance_m) + " off the ground at its feet";
  const std::string name = worst->name.empty() ? "a box" : std::string(box_kind_name(worst->kind)) + " '" + worst->name + "'";
  return body + " overlaps " + name + " by " + metres(depth) + ": it lacks that much room";
}

}  // namespace foresight

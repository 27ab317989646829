#pragma once
// Helpers shared by the tests of shared/world: built-in scene loading, a brute-force reference
// collision check (no grid, no precomputation) and synthetic placements.
#include "world/collision_check.hpp"
#include "world/collision_world.hpp"
#include "world/scene_load.hpp"
#include "world/synthetic_sweep.hpp"
#include "world/terrain.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace foresight::test {

inline std::filesystem::path scenes_dir() {
  return std::filesystem::path(FORESIGHT_DATA_DIR) / "scenes";
}

inline Scene load_builtin_scene(const std::string& name) {
  Scene scene;
  std::string error;
  EXPECT_TRUE(scene_load(scenes_dir() / (name + ".json"), scene, error)) << error;
  return scene;
}

inline CollisionWorld build_world(const Scene& scene, const CollisionWorldConfig& config = {}) {
  CollisionWorld world;
  std::string error;
  EXPECT_TRUE(collision_world_build(scene, world, error, config)) << error;
  return world;
}

/// Does the capsule touch the box's ground rectangle? Written independently of
/// capsule_overlaps_rect: an end inside the rectangle, or the core within r of an edge.
inline bool brute_capsule_touches(const BodyVolume& v, const SceneBox& b) {
  const vec2 p0 = v.center_m - v.half_axis_m, p1 = v.center_m + v.half_axis_m;
  const auto inside = [&](vec2 p) {
    return p.x >= b.min_m.x && p.x <= b.max_m.x && p.y >= b.min_m.z && p.y <= b.max_m.z;
  };
  if (inside(p0) || inside(p1)) return true;
  const vec2 c[4] = {{b.min_m.x, b.min_m.z}, {b.max_m.x, b.min_m.z}, {b.max_m.x, b.max_m.z}, {b.min_m.x, b.max_m.z}};
  for (int i = 0; i < 4; ++i) {
    const float d2 = segment_distance_sq(p0, p1, c[i], c[(i + 1) % 4]);
    if (d2 <= 1e-8f || d2 < v.radius_m * v.radius_m) return true;  // a crossing rounds to ~0 (long edges)
  }
  return false;
}

/// The collision model written as plainly as possible: every box, the scene's own terrain.
inline bool brute_frame_collides(const Scene& scene, const BodyVolume& v, float ground_ref_y_m,
                                 float tolerance_m) {
  if (!scene.bounds.contains(v.center_m)) return true;
  float g = 0.0f;
  if (!terrain_height_at(scene.terrain, v.center_m, g)) return true;
  if (!(g >= ground_ref_y_m - tolerance_m && g <= ground_ref_y_m + tolerance_m)) return true;
  for (const SceneBox& b : scene.boxes) {
    if (brute_capsule_touches(v, b) && y_ranges_overlap(v.y_min_m, v.y_max_m, b.min_m.y, b.max_m.y))
      return true;
  }
  return false;
}

/// First colliding frame (time order) of `frames` placed at `start`, -1 if none, 0 when the start
/// has no ground: the reference for segment_feasible / segment_first_collision.
inline int brute_first_collision(const Scene& scene, std::span<const BodyVolume> frames,
                                 const Placement& start, float tolerance_m) {
  float h0 = 0.0f;
  if (!scene.bounds.contains(start.pos_m) || !terrain_height_at(scene.terrain, start.pos_m, h0))
    return 0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    BodyVolume w = place(frames[i], start);
    w.y_min_m = frames[i].y_min_m + h0;
    w.y_max_m = frames[i].y_max_m + h0;
    if (brute_frame_collides(scene, w, h0, tolerance_m)) return static_cast<int>(i);
  }
  return -1;
}

inline Placement placement_deg(float x, float z, float heading_deg) {
  return {vec2(x, z), radians(heading_deg)};
}

}  // namespace foresight::test

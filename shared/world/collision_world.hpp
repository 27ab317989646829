#pragma once
// The scene compiled for collision queries: a uniform grid on the ground plane whose cells hold
// copies of the boxes near them (hot data only, contiguous), per-cell ground ranges, and a
// clearance field for whole-sweep early-outs. Built once per scene; read-only afterwards, so any
// number of threads may query one world. Queries: collision_check.hpp.
//
// Collision model (docs/SCENES.md):
//  * Body: one vertical capsule per frame (BodyVolume: ground capsule + y range).
//  * Box: overlaps the body when the capsule's core segment is within distance < radius of the
//    box's ground rectangle (or touches it) AND the y ranges overlap strictly (box.min_y < y_max and
//    box.max_y > y_min). Touching is not a collision; a box whose top is at or below the body's
//    feet, or whose bottom is at or above its head, is passed (tables, lintels, crouching).
//  * Bounds: a frame whose capsule centre is outside the scene bounds is blocked.
//  * Terrain, for clips authored on flat ground: a frame is blocked when there is no ground under
//    its capsule centre or the ground there differs from a reference height (the ground at the
//    segment's start) by more than ground_tolerance_m. Real footstep planning on uneven ground is
//    the terrain planner's job; this rule only keeps flat clips on nearly flat ground.
#include "world/scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace foresight {

struct CollisionWorldConfig {
  /// Grid cell size. Smaller cells hold fewer boxes but cost memory; 0.5 m suits rooms and
  /// corridors. Raised automatically so that no axis has more than kMaxGridCellsPerAxis cells.
  float cell_m = 0.5f;
  /// Boxes are registered in every cell within this distance, so a disc of radius up to this
  /// needs only the cell of its centre (one lookup). Larger discs scan neighbour cells.
  float fast_radius_m = 0.6f;
  /// Terrain rule tolerance: a small step up or down is fine for a flat clip.
  float ground_tolerance_m = 0.25f;
  /// The clearance field is exact up to this distance (larger sweeps never early-out).
  float max_clearance_m = 3.0f;
};

inline constexpr int kMaxGridCellsPerAxis = 2048;
/// Cap on box copies over all cells (24 bytes each), against absurdly dense scenes.
inline constexpr std::uint64_t kMaxGridBoxRefs = 16u << 20;

/// A box as the hot loop reads it: ground rectangle and y range, 24 bytes, no indirection.
struct CellBox {
  float min_x, min_z, max_x, max_z;
  float min_y, max_y;
};

struct GridCell {
  std::uint32_t first_box = 0;  ///< Range into CollisionWorld::cell_boxes.
  std::uint32_t num_boxes = 0;
  /// Bounds on the ground height anywhere in the cell. When the cell may have holes these are
  /// -inf / +inf, so the fast tolerance test fails and the exact query runs.
  float ground_lo_m = 0.0f;
  float ground_hi_m = 0.0f;
};

struct CollisionWorld {
  CollisionWorldConfig config;
  GroundRect bounds;  ///< The grid starts at bounds.min_m.
  float cell_m = 1.0f;
  float inv_cell_m = 1.0f;
  int cells_x = 0;
  int cells_z = 0;
  std::vector<GridCell> cells;      ///< [iz * cells_x + ix]
  std::vector<CellBox> cell_boxes;  ///< Boxes near each cell, cell after cell.
  /// Per cell: a lower bound on the distance from any point of the cell to any box, to the
  /// outside of the bounds and to any ground that is not flat floor (minus a rounding margin).
  std::vector<float> clearance_m;
  std::vector<CellBox> boxes;  ///< Every scene box once, in scene order (reference, debugging).
  Terrain terrain;             ///< For exact ground queries.
  std::vector<std::uint32_t> step_first;  ///< cells + 1 offsets into step_refs.
  std::vector<std::uint32_t> step_refs;   ///< Indices into terrain.steps near each cell.

  bool empty() const { return cells.empty(); }
  int cell_index(int ix, int iz) const { return iz * cells_x + ix; }
  /// The cell of a point inside the bounds (the far edges map to the last row/column).
  int cell_of(vec2 p_m) const {
    const int ix = std::min(static_cast<int>((p_m.x - bounds.min_m.x) * inv_cell_m), cells_x - 1);
    const int iz = std::min(static_cast<int>((p_m.y - bounds.min_m.y) * inv_cell_m), cells_z - 1);
    return iz * cells_x + ix;
  }
};

/// Compiles a (validated) scene. False with a message when the scene is too large or dense for the
/// grid caps, or has invalid bounds. `world` is replaced only on success.
bool collision_world_build(const Scene& scene, CollisionWorld& world, std::string& error,
                           const CollisionWorldConfig& config = {});

/// Exact ground height at p (same answer as terrain_height_at on the scene's terrain), false
/// outside the bounds or over a hole.
bool ground_height_at(const CollisionWorld& world, vec2 p_m, float& height_m);

/// ground_height_at for a point already known to lie in the bounds and in cell `cell`
/// (cell == world.cell_of(p_m)).
bool ground_height_in_cell(const CollisionWorld& world, int cell, vec2 p_m, float& height_m);

/// The box test of the model above, shared by the grid and brute-force reference code.
inline bool disc_overlaps_rect(float cx, float cz, float radius, float min_x, float min_z,
                               float max_x, float max_z) {
  const float dx = std::max(std::max(min_x - cx, cx - max_x), 0.0f);
  const float dz = std::max(std::max(min_z - cz, cz - max_z), 0.0f);
  const float d2 = dx * dx + dz * dz;
  // d2 == 0: the centre is inside the (closed) rectangle, a hit even for a zero radius.
  return d2 < radius * radius || d2 == 0.0f;
}

/// The box test for a capsule: core segment centre (cx, cz) +- (ax, az), grown by `radius`.
/// Same rule as disc_overlaps_rect (a zero half axis gives the same answer).
inline bool capsule_overlaps_rect(float cx, float cz, float ax, float az, float radius, float min_x,
                                  float min_z, float max_x, float max_z) {
  if (ax == 0.0f && az == 0.0f) return disc_overlaps_rect(cx, cz, radius, min_x, min_z, max_x, max_z);
  // Bounding boxes apart by at least the radius: no point of the segment is nearer than that.
  const float ex = std::abs(ax) + radius, ez = std::abs(az) + radius;
  if (cx - ex >= max_x || cx + ex <= min_x || cz - ez >= max_z || cz + ez <= min_z) return false;
  // Does the segment touch the closed rectangle (Liang-Barsky clip)?
  const float x0 = cx - ax, z0 = cz - az, dx = 2.0f * ax, dz = 2.0f * az;
  float t0 = 0.0f, t1 = 1.0f;
  const auto clip = [&](float p, float q) {  // keeps t with p * t <= q
    if (p == 0.0f) return q >= 0.0f;
    const float t = q / p;
    if (p < 0.0f) t0 = std::max(t0, t);
    else t1 = std::min(t1, t);
    return t0 <= t1;
  };
  if (clip(-dx, x0 - min_x) && clip(dx, max_x - x0) && clip(-dz, z0 - min_z) && clip(dz, max_z - z0))
    return true;
  // Apart: the nearest pair is a segment end and the rectangle, or a corner and the segment.
  const auto point_rect = [&](float x, float z) {
    const float ox = std::max(std::max(min_x - x, x - max_x), 0.0f);
    const float oz = std::max(std::max(min_z - z, z - max_z), 0.0f);
    return ox * ox + oz * oz;
  };
  const float len2 = dx * dx + dz * dz;
  const auto corner_segment = [&](float x, float z) {
    const float t = std::clamp(((x - x0) * dx + (z - z0) * dz) / len2, 0.0f, 1.0f);
    const float ox = x0 + t * dx - x, oz = z0 + t * dz - z;
    return ox * ox + oz * oz;
  };
  const float d2 = std::min({point_rect(x0, z0), point_rect(x0 + dx, z0 + dz), corner_segment(min_x, min_z),
                             corner_segment(min_x, max_z), corner_segment(max_x, min_z),
                             corner_segment(max_x, max_z)});
  return d2 < radius * radius;
}

inline bool y_ranges_overlap(float body_min_y, float body_max_y, float box_min_y,
                             float box_max_y) {
  return box_min_y < body_max_y && box_max_y > body_min_y;
}

}  // namespace foresight

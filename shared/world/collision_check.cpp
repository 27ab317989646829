#include "world/collision_check.hpp"

#include <cmath>

namespace foresight {
namespace {

/// The sweep disc must clear the field by this much more than its radius: the field's margin
/// covers rounding in the cell index, this covers rounding in the placed frame centres.
constexpr float kSweepMargin_m = 1e-3f;

bool in_bounds(const GroundRect& b, float x, float z) {
  // Written so that NaN fails.
  return x >= b.min_m.x && x <= b.max_m.x && z >= b.min_m.y && z <= b.max_m.y;
}

/// A frame's footprint, placed: capsule centre, half axis, radius, height range.
struct Footprint {
  float x, z, ax, az, r, y0, y1;
};

bool hits_any(const CellBox* box, std::uint32_t n, const Footprint& f) {
  for (const CellBox* end = box + n; box != end; ++box) {
    // Most boxes near a body are walls (always in the y range), so the plane test goes first.
    if (capsule_overlaps_rect(f.x, f.z, f.ax, f.az, f.r, box->min_x, box->min_z, box->max_x, box->max_z) &&
        y_ranges_overlap(f.y0, f.y1, box->min_y, box->max_y))
      return true;
  }
  return false;
}

/// Footprints reaching further than fast_radius_m: boxes are registered fast_radius_m around
/// themselves, so a box within `reach` of the centre is registered in some cell within
/// reach - fast_radius_m of it.
bool hits_any_wide(const CollisionWorld& w, const Footprint& f, float reach) {
  const float extra = reach - w.config.fast_radius_m;
  const float x = f.x, z = f.z;
  const auto cell = [&](float v, float origin, int n) {
    return static_cast<int>(
        std::clamp(std::floor((v - origin) * w.inv_cell_m), 0.0f, static_cast<float>(n - 1)));
  };
  const int x0 = cell(x - extra, w.bounds.min_m.x, w.cells_x);
  const int x1 = cell(x + extra, w.bounds.min_m.x, w.cells_x);
  const int z0 = cell(z - extra, w.bounds.min_m.y, w.cells_z);
  const int z1 = cell(z + extra, w.bounds.min_m.y, w.cells_z);
  for (int iz = z0; iz <= z1; ++iz) {
    for (int ix = x0; ix <= x1; ++ix) {
      const GridCell& c = w.cells[w.cell_index(ix, iz)];
      if (hits_any(w.cell_boxes.data() + c.first_box, c.num_boxes, f)) return true;
    }
  }
  return false;
}

/// The box part of the per-frame test, for a footprint whose centre lies in the bounds, in `cell`.
inline bool boxes_hit(const CollisionWorld& w, const Footprint& f, const GridCell& cell) {
  // Footprint within fast_radius_m of its centre (|half axis| + r <= fast): one cell holds every box.
  const float core = w.config.fast_radius_m - f.r, half2 = f.ax * f.ax + f.az * f.az;
  if (core >= 0.0f && half2 <= core * core)
    return hits_any(w.cell_boxes.data() + cell.first_box, cell.num_boxes, f);
  const float reach = std::sqrt(half2) + f.r;
  if (!std::isfinite(reach)) return true;
  return hits_any_wide(w, f, reach);
}

/// The whole per-frame test. ground_lo/hi: the accepted ground range (reference -+ tolerance).
inline bool frame_blocked(const CollisionWorld& w, const Footprint& f, float ground_lo, float ground_hi) {
  if (!in_bounds(w.bounds, f.x, f.z)) return true;
  const int ci = w.cell_of({f.x, f.z});
  const GridCell& cell = w.cells[static_cast<std::size_t>(ci)];
  // Fast path: every ground height in the cell is acceptable. Holes make lo/hi -inf/+inf.
  if (!(cell.ground_lo_m >= ground_lo && cell.ground_hi_m <= ground_hi)) {
    float g = 0.0f;
    if (!ground_height_in_cell(w, ci, {f.x, f.z}, g) || !(g >= ground_lo && g <= ground_hi))
      return true;
  }
  return boxes_hit(w, f, cell);
}

/// A segment-local frame placed at (c, sn, pos) = (cos, sin of the heading, position), its heights
/// raised by h0. Same arithmetic as Placement::apply / rotate_ground.
inline Footprint placed(const BodyVolume& v, float c, float sn, vec2 pos, float h0) {
  return {c * v.center_m.x + sn * v.center_m.y + pos.x, -sn * v.center_m.x + c * v.center_m.y + pos.y,
          c * v.half_axis_m.x + sn * v.half_axis_m.y, -sn * v.half_axis_m.x + c * v.half_axis_m.y,
          v.radius_m, v.y_min_m + h0, v.y_max_m + h0};
}

/// The placed sweep disc lies where nothing can be hit: every frame is free, without testing any.
inline bool sweep_clear(const CollisionWorld& w, const SegmentCollisionShape& s, float c, float sn,
                        vec2 pos) {
  const vec2 v = s.sweep_center_m;
  const float x = c * v.x + sn * v.y + pos.x;
  const float z = -sn * v.x + c * v.y + pos.y;
  if (!in_bounds(w.bounds, x, z)) return false;
  return s.sweep_radius_m + kSweepMargin_m <= w.clearance_m[static_cast<std::size_t>(w.cell_of({x, z}))];
}

}  // namespace

bool frame_collides(const CollisionWorld& world, const BodyVolume& v, float ground_ref_y_m) {
  if (world.empty()) return true;
  const float tol = world.config.ground_tolerance_m;
  return frame_blocked(world, placed(v, 1.0f, 0.0f, vec2(0.0f), 0.0f), ground_ref_y_m - tol,
                       ground_ref_y_m + tol);
}

bool volume_hits_boxes(const CollisionWorld& world, const BodyVolume& v) {
  if (world.empty()) return true;
  const Footprint f = placed(v, 1.0f, 0.0f, vec2(0.0f), 0.0f);
  if (!in_bounds(world.bounds, f.x, f.z)) return true;
  return boxes_hit(world, f, world.cells[static_cast<std::size_t>(world.cell_of({f.x, f.z}))]);
}

bool segment_feasible(const CollisionWorld& world, const SegmentCollisionShape& shape,
                      const Placement& start, CheckStats* stats) {
  if (stats != nullptr) ++stats->clip_checks;
  if (world.empty()) return false;
  // Same arithmetic as Placement::apply / rotate_ground, so results match placing each frame.
  const float c = std::cos(start.heading_rad), sn = std::sin(start.heading_rad);
  const vec2 pos = start.pos_m;

  // The sweep disc contains the start point, so when it is clear the start is on flat floor too.
  if (sweep_clear(world, shape, c, sn, pos)) {
    if (stats != nullptr) {
      ++stats->sweep_early_outs;
      ++stats->feasible_clips;
    }
    return true;
  }

  float h0 = 0.0f;
  if (!ground_height_at(world, pos, h0)) return false;
  const float tol = world.config.ground_tolerance_m;
  const float ground_lo = h0 - tol, ground_hi = h0 + tol;

  std::uint64_t checked = 0;
  bool feasible = true;
  for (const BodyVolume& f : shape.check_frames) {
    ++checked;
    if (frame_blocked(world, placed(f, c, sn, pos, h0), ground_lo, ground_hi)) {
      feasible = false;
      break;
    }
  }
  if (stats != nullptr) {
    stats->frame_checks += checked;
    stats->feasible_clips += feasible ? 1 : 0;
  }
  return feasible;
}

int segment_first_collision(const CollisionWorld& world, const SegmentCollisionShape& shape,
                            const Placement& start) {
  if (world.empty()) return 0;
  const float c = std::cos(start.heading_rad), sn = std::sin(start.heading_rad);
  const vec2 pos = start.pos_m;
  if (sweep_clear(world, shape, c, sn, pos)) return -1;
  float h0 = 0.0f;
  if (!ground_height_at(world, pos, h0)) return 0;
  const float tol = world.config.ground_tolerance_m;
  for (std::size_t i = 0; i < shape.frames.size(); ++i) {
    const BodyVolume& f = shape.frames[i];
    if (frame_blocked(world, placed(f, c, sn, pos, h0), h0 - tol, h0 + tol))
      return static_cast<int>(i);
  }
  return -1;
}

}  // namespace foresight

#include "world/collision_world.hpp"

#include "world/terrain.hpp"

#include <cmath>
#include <limits>

namespace foresight {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

struct CellRange {
  int x0, x1, z0, z1;
  std::size_t count() const {
    return static_cast<std::size_t>(x1 - x0 + 1) * static_cast<std::size_t>(z1 - z0 + 1);
  }
};

int clamp_cell(float f, int n) {
  // Clamp in float first: a far-away coordinate must not overflow the int conversion.
  return static_cast<int>(std::clamp(std::floor(f), 0.0f, static_cast<float>(n - 1)));
}

/// Cells whose rectangles meet [lo, hi], clamped to the grid. Something outside the grid maps to
/// the nearest edge cells: queries clamp the same way, so a box just outside the bounds is still
/// found by a large disc centred at the edge.
CellRange cells_of(const CollisionWorld& w, vec2 lo, vec2 hi) {
  const vec2 o = w.bounds.min_m;
  return {clamp_cell((lo.x - o.x) * w.inv_cell_m, w.cells_x),
          clamp_cell((hi.x - o.x) * w.inv_cell_m, w.cells_x),
          clamp_cell((lo.y - o.y) * w.inv_cell_m, w.cells_z),
          clamp_cell((hi.y - o.y) * w.inv_cell_m, w.cells_z)};
}

GroundRect cell_rect(const CollisionWorld& w, int ix, int iz) {
  const vec2 lo = w.bounds.min_m + vec2(static_cast<float>(ix), static_cast<float>(iz)) * w.cell_m;
  return {lo, lo + vec2(w.cell_m)};
}

GroundRect grown(const GroundRect& r, float by) { return {r.min_m - vec2(by), r.max_m + vec2(by)}; }

float rect_distance(const GroundRect& a, const GroundRect& b) {
  const float dx = std::max({a.min_m.x - b.max_m.x, b.min_m.x - a.max_m.x, 0.0f});
  const float dz = std::max({a.min_m.y - b.max_m.y, b.min_m.y - a.max_m.y, 0.0f});
  return std::sqrt(dx * dx + dz * dz);
}

CellBox cell_box_of(const SceneBox& b) {
  return {b.min_m.x, b.min_m.z, b.max_m.x, b.max_m.z, b.min_m.y, b.max_m.y};
}

bool build_boxes(const Scene& scene, CollisionWorld& w, float eps, std::string& error) {
  // Two passes (count, then fill) so every cell's boxes are contiguous in one array.
  const float reach = w.config.fast_radius_m + eps;
  const std::size_t num_cells = w.cells.size();
  std::vector<std::uint32_t> counts(num_cells, 0);
  std::uint64_t total = 0;
  for (const SceneBox& b : scene.boxes) {
    const GroundRect r = grown(b.ground_rect(), reach);
    total += cells_of(w, r.min_m, r.max_m).count();
  }
  if (total > kMaxGridBoxRefs) {
    error = "scene \"" + scene.name + "\" is too dense for the collision grid: " +
            std::to_string(total) + " box copies over the cells (max " +
            std::to_string(kMaxGridBoxRefs) + ")";
    return false;
  }
  for (const SceneBox& b : scene.boxes) {
    const GroundRect r = grown(b.ground_rect(), reach);
    const CellRange c = cells_of(w, r.min_m, r.max_m);
    for (int iz = c.z0; iz <= c.z1; ++iz)
      for (int ix = c.x0; ix <= c.x1; ++ix) ++counts[w.cell_index(ix, iz)];
  }
  std::uint32_t first = 0;
  for (std::size_t i = 0; i < num_cells; ++i) {
    w.cells[i].first_box = first;
    w.cells[i].num_boxes = 0;
    first += counts[i];
  }
  w.cell_boxes.resize(first);
  w.boxes.reserve(scene.boxes.size());
  for (const SceneBox& b : scene.boxes) {
    const CellBox cb = cell_box_of(b);
    w.boxes.push_back(cb);
    const GroundRect r = grown(b.ground_rect(), reach);
    const CellRange c = cells_of(w, r.min_m, r.max_m);
    for (int iz = c.z0; iz <= c.z1; ++iz) {
      for (int ix = c.x0; ix <= c.x1; ++ix) {
        GridCell& cell = w.cells[w.cell_index(ix, iz)];
        w.cell_boxes[cell.first_box + cell.num_boxes++] = cb;
      }
    }
  }
  return true;
}

/// Which steps each cell must consult for exact ground queries (same layout as the boxes).
bool build_steps(CollisionWorld& w, float eps, std::string& error) {
  const Terrain& t = w.terrain;
  const std::size_t num_cells = w.cells.size();
  std::vector<std::uint32_t> counts(num_cells, 0);
  std::uint64_t total = 0;
  for (const StepBlock& s : t.steps) {
    const GroundRect r = grown(s.ground_rect(), eps);
    total += cells_of(w, r.min_m, r.max_m).count();
  }
  if (total > kMaxGridBoxRefs) {
    error = "terrain steps are too dense for the collision grid: " + std::to_string(total) +
            " step copies over the cells (max " + std::to_string(kMaxGridBoxRefs) + ")";
    return false;
  }
  for (const StepBlock& s : t.steps) {
    const GroundRect r = grown(s.ground_rect(), eps);
    const CellRange c = cells_of(w, r.min_m, r.max_m);
    for (int iz = c.z0; iz <= c.z1; ++iz)
      for (int ix = c.x0; ix <= c.x1; ++ix) ++counts[w.cell_index(ix, iz)];
  }
  w.step_first.assign(num_cells + 1, 0);
  for (std::size_t i = 0; i < num_cells; ++i) w.step_first[i + 1] = w.step_first[i] + counts[i];
  w.step_refs.resize(w.step_first[num_cells]);
  std::fill(counts.begin(), counts.end(), 0u);
  for (std::size_t si = 0; si < t.steps.size(); ++si) {
    const GroundRect r = grown(t.steps[si].ground_rect(), eps);
    const CellRange c = cells_of(w, r.min_m, r.max_m);
    for (int iz = c.z0; iz <= c.z1; ++iz) {
      for (int ix = c.x0; ix <= c.x1; ++ix) {
        const int ci = w.cell_index(ix, iz);
        w.step_refs[w.step_first[ci] + counts[ci]++] = static_cast<std::uint32_t>(si);
      }
    }
  }
  return true;
}

/// Conservative ground range of each cell. Returns per cell whether the ground there is exactly
/// the flat floor (what the clearance field treats as free).
std::vector<std::uint8_t> build_ground(CollisionWorld& w, float eps) {
  const Terrain& t = w.terrain;
  const HeightField& field = t.height_field;
  const GroundRect field_rect = field.extent();
  const std::size_t num_cells = w.cells.size();

  std::vector<std::uint8_t> flat_floor(num_cells, 0);
  for (int iz = 0; iz < w.cells_z; ++iz) {
    for (int ix = 0; ix < w.cells_x; ++ix) {
      const int ci = w.cell_index(ix, iz);
      // Grown by eps: a point assigned to this cell by rounding may lie just outside it.
      const GroundRect r = grown(cell_rect(w, ix, iz), eps);
      float lo = kInf, hi = -kInf;
      bool maybe_hole = false;
      const bool inside_field = !field.empty() && r.min_m.x >= field_rect.min_m.x &&
                                r.max_m.x < field_rect.max_m.x && r.min_m.y >= field_rect.min_m.y &&
                                r.max_m.y < field_rect.max_m.y;
      if (!inside_field) lo = hi = t.floor_y_m;  // Some of the cell may be plain floor.
      if (!field.empty() && r.intersects(field_rect)) {
        const auto field_cell = [&](float v, float origin, int n) {
          return static_cast<int>(
              std::clamp(std::floor((v - origin) / field.cell_m), 0.0f, static_cast<float>(n - 1)));
        };
        const int fx0 = field_cell(r.min_m.x, field.origin_m.x, field.count_x);
        const int fx1 = field_cell(r.max_m.x, field.origin_m.x, field.count_x);
        const int fz0 = field_cell(r.min_m.y, field.origin_m.y, field.count_z);
        const int fz1 = field_cell(r.max_m.y, field.origin_m.y, field.count_z);
        for (int fz = fz0; fz <= fz1 && !maybe_hole; ++fz) {
          for (int fx = fx0; fx <= fx1; ++fx) {
            const float h = field.heights_m[static_cast<std::size_t>(fz) * field.count_x + fx];
            if (std::isnan(h)) {
              maybe_hole = true;
              break;
            }
            lo = std::min(lo, h);
            hi = std::max(hi, h);
          }
        }
      }
      // Steps only raise the ground (never below the base), so they widen hi only.
      for (std::uint32_t k = w.step_first[ci]; k < w.step_first[ci + 1]; ++k)
        hi = std::max(hi, t.steps[w.step_refs[k]].max_m.y);
      GridCell& cell = w.cells[ci];
      if (maybe_hole) {
        // An unbounded range fails every fast tolerance test: the exact query runs.
        cell.ground_lo_m = -kInf;
        cell.ground_hi_m = kInf;
      } else {
        cell.ground_lo_m = lo;
        cell.ground_hi_m = hi;
        flat_floor[ci] = lo == t.floor_y_m && hi == t.floor_y_m;
      }
    }
  }
  return flat_floor;
}

void build_clearance(const Scene& scene, CollisionWorld& w, const std::vector<std::uint8_t>& flat,
                     float eps) {
  const float cap = w.config.max_clearance_m;
  const GroundRect& b = w.bounds;
  w.clearance_m.assign(w.cells.size(), cap);
  // Distance to the outside of the bounds.
  for (int iz = 0; iz < w.cells_z; ++iz) {
    for (int ix = 0; ix < w.cells_x; ++ix) {
      const GroundRect r = cell_rect(w, ix, iz);
      const float d = std::min({r.min_m.x - b.min_m.x, b.max_m.x - r.max_m.x,
                                r.min_m.y - b.min_m.y, b.max_m.y - r.max_m.y});
      float& c = w.clearance_m[w.cell_index(ix, iz)];
      c = std::min(c, std::max(d, 0.0f));
    }
  }
  // Exact rectangle distance to every box within the cap. Every box counts, whatever its height:
  // the field must hold for any body.
  for (const SceneBox& box : scene.boxes) {
    const GroundRect br = box.ground_rect();
    const GroundRect reach = grown(br, cap);
    const CellRange c = cells_of(w, reach.min_m, reach.max_m);
    for (int iz = c.z0; iz <= c.z1; ++iz) {
      for (int ix = c.x0; ix <= c.x1; ++ix) {
        float& cl = w.clearance_m[w.cell_index(ix, iz)];
        cl = std::min(cl, rect_distance(cell_rect(w, ix, iz), br));
      }
    }
  }
  // Ground that is not flat floor: Chebyshev distance in cells (two-pass chamfer, exact for that
  // metric) gives a lower bound of (k - 1) cells, in O(cells) however much terrain there is.
  const int nx = w.cells_x, nz = w.cells_z;
  constexpr int kFar = std::numeric_limits<int>::max() / 2;
  std::vector<int> k(w.cells.size());
  bool any = false;
  for (std::size_t i = 0; i < k.size(); ++i) {
    k[i] = flat[i] ? kFar : 0;
    any = any || !flat[i];
  }
  if (any) {
    for (int iz = 0; iz < nz; ++iz) {
      for (int ix = 0; ix < nx; ++ix) {
        int& v = k[w.cell_index(ix, iz)];
        if (ix > 0) v = std::min(v, k[w.cell_index(ix - 1, iz)] + 1);
        if (iz > 0) {
          for (int dx = -1; dx <= 1; ++dx)
            if (ix + dx >= 0 && ix + dx < nx) v = std::min(v, k[w.cell_index(ix + dx, iz - 1)] + 1);
        }
      }
    }
    for (int iz = nz - 1; iz >= 0; --iz) {
      for (int ix = nx - 1; ix >= 0; --ix) {
        int& v = k[w.cell_index(ix, iz)];
        if (ix + 1 < nx) v = std::min(v, k[w.cell_index(ix + 1, iz)] + 1);
        if (iz + 1 < nz) {
          for (int dx = -1; dx <= 1; ++dx)
            if (ix + dx >= 0 && ix + dx < nx) v = std::min(v, k[w.cell_index(ix + dx, iz + 1)] + 1);
        }
      }
    }
    for (std::size_t i = 0; i < k.size(); ++i) {
      const float d = static_cast<float>(std::max(k[i] - 1, 0)) * w.cell_m;
      w.clearance_m[i] = std::min(w.clearance_m[i], d);
    }
  }
  // The margin covers rounding in the cell index of a query point and in placed positions.
  for (float& c : w.clearance_m) c = std::max(c - eps, 0.0f);
}

}  // namespace

bool collision_world_build(const Scene& scene, CollisionWorld& world, std::string& error,
                           const CollisionWorldConfig& config) {
  const GroundRect& b = scene.bounds;
  const vec2 size = b.size_m();
  if (!(std::isfinite(b.min_m.x) && std::isfinite(b.min_m.y) && std::isfinite(b.max_m.x) &&
        std::isfinite(b.max_m.y) && size.x > 0.0f && size.y > 0.0f &&
        size.x <= kMaxSceneExtent_m && size.y <= kMaxSceneExtent_m)) {
    error = "scene \"" + scene.name + "\": bounds must be finite, non-empty and at most " +
            std::to_string(kMaxSceneExtent_m) + " m per side";
    return false;
  }
  if (!(config.cell_m > 0.0f && config.fast_radius_m >= 0.0f &&
        config.ground_tolerance_m >= 0.0f && config.max_clearance_m >= 0.0f)) {
    error = "collision world config: sizes must be positive";
    return false;
  }

  CollisionWorld w;
  w.config = config;
  w.bounds = b;
  w.cell_m = std::max({config.cell_m, size.x / kMaxGridCellsPerAxis, size.y / kMaxGridCellsPerAxis});
  w.inv_cell_m = 1.0f / w.cell_m;
  w.cells_x = std::clamp(static_cast<int>(std::ceil(size.x * w.inv_cell_m)), 1, kMaxGridCellsPerAxis);
  w.cells_z = std::clamp(static_cast<int>(std::ceil(size.y * w.inv_cell_m)), 1, kMaxGridCellsPerAxis);
  // Rounding in ceil() may leave the last column a hair short of the bounds; queries clamp the
  // cell index, so that sliver maps to the last cell, which the eps-grown rectangles cover.
  w.cells.resize(static_cast<std::size_t>(w.cells_x) * w.cells_z);
  w.terrain = scene.terrain;
  const float magnitude = std::max({std::abs(b.min_m.x), std::abs(b.min_m.y), std::abs(b.max_m.x),
                                    std::abs(b.max_m.y)});
  const float eps = 1e-3f + 4e-6f * magnitude;

  if (!build_boxes(scene, w, eps, error) || !build_steps(w, eps, error)) return false;
  const std::vector<std::uint8_t> flat = build_ground(w, eps);
  build_clearance(scene, w, flat, eps);
  world = std::move(w);
  return true;
}

bool ground_height_at(const CollisionWorld& world, vec2 p_m, float& height_m) {
  if (world.empty() || !world.bounds.contains(p_m)) return false;
  return ground_height_in_cell(world, world.cell_of(p_m), p_m, height_m);
}

bool ground_height_in_cell(const CollisionWorld& world, int cell, vec2 p_m, float& height_m) {
  // Only the steps registered near this cell can cover p, so the answer equals terrain_height_at.
  const std::uint32_t first = world.step_first[static_cast<size_t>(cell)];
  const int count = static_cast<int>(world.step_first[static_cast<size_t>(cell) + 1] - first);
  return terrain_height_over_steps(
      world.terrain, p_m, count,
      [&](int k) -> const StepBlock& {
        return world.terrain.steps[world.step_refs[first + static_cast<std::uint32_t>(k)]];
      },
      height_m);
}

}  // namespace foresight

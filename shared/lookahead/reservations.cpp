#include "lookahead/reservations.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace foresight {

namespace {

/// place() for every frame of one segment, the heading's cosine and sine taken once (the same
/// arithmetic as rotate_ground, so the same placed volumes).
struct Placer {
  explicit Placer(const Placement& p) : c(std::cos(p.heading_rad)), s(std::sin(p.heading_rad)), pos_m(p.pos_m) {}
  vec2 rotate(vec2 v) const { return {c * v.x + s * v.y, -s * v.x + c * v.y}; }
  BodyVolume operator()(const BodyVolume& v) const {
    return {rotate(v.center_m) + pos_m, v.radius_m, v.y_min_m, v.y_max_m, rotate(v.half_axis_m)};
  }
  float c, s;
  vec2 pos_m;
};

/// The disc and box tests are bounds on the capsule test; this slack keeps a rounding error in
/// them from skipping a pair that the capsule test would find touching.
constexpr float kSlack_m = 1e-3f;

}  // namespace

void Reservations::configure(const GroundRect& bounds, float cell_m, float clearance_m) {
  cell_m_ = std::max(cell_m, 0.25f);
  clearance_m_ = clearance_m;
  // One ring of cells past the bounds: avatars stand inside, but their footprints may poke out.
  origin_m_ = bounds.min_m - vec2(cell_m_);
  const vec2 size = bounds.max_m - bounds.min_m + vec2(2.0f * cell_m_);
  count_x_ = std::clamp(static_cast<int>(std::ceil(size.x / cell_m_)), 1, 4096);
  count_z_ = std::clamp(static_cast<int>(std::ceil(size.y / cell_m_)), 1, 4096);
  cells_.assign(static_cast<size_t>(count_x_) * static_cast<size_t>(count_z_), {});
  touched_.clear();
  bodies_.clear();
  runs_.clear();
}

void Reservations::clear() {
  for (int c : touched_) cells_[static_cast<size_t>(c)].clear();
  touched_.clear();
  bodies_.clear();
  runs_.clear();
}

// Clamped to the grid (NaN to the first cell), monotone: a box's cells are those of its corners.
int Reservations::cell_along(float v, float origin, int count) const {
  const float f = std::floor((v - origin) / cell_m_);
  if (!(f > 0.0f)) return 0;
  return f >= static_cast<float>(count - 1) ? count - 1 : static_cast<int>(f);
}

// The frames from `from` on, placed at `start`, with the box their discs fill.
void Reservations::place_frames(std::span<const BodyVolume> frames, size_t from, const Placement& start,
                                std::vector<Reserved>& out, vec2& lo, vec2& hi) {
  const Placer placer(start);
  constexpr float kInf = std::numeric_limits<float>::infinity();
  lo = vec2(kInf), hi = vec2(-kInf);
  for (size_t f = from; f < frames.size(); ++f) {
    const BodyVolume v = placer(frames[f]);
    const float reach = v.reach_m();
    out.push_back({v, reach});
    lo = glm::min(lo, v.center_m - vec2(reach));
    hi = glm::max(hi, v.center_m + vec2(reach));
  }
}

void Reservations::add(int owner, const MotionLibrary& library, int segment, int from_frame,
                       const Placement& start) {
  const auto frames = library.volumes(segment);
  const size_t from = static_cast<size_t>(std::max(from_frame, 0));
  if (from >= frames.size()) return;
  Run run{vec2(0.0f), vec2(0.0f), static_cast<int>(bodies_.size()), 0, owner};
  place_frames(frames, from, start, bodies_, run.lo_m, run.hi_m);
  run.end = static_cast<int>(bodies_.size());
  const int index = static_cast<int>(runs_.size());
  runs_.push_back(run);
  for (int z = cell_z(run.lo_m.y), z1 = cell_z(run.hi_m.y); z <= z1; ++z)
    for (int x = cell_x(run.lo_m.x), x1 = cell_x(run.hi_m.x); x <= x1; ++x) {
      const int cell = z * count_x_ + x;
      auto& list = cells_[static_cast<size_t>(cell)];
      if (list.empty()) touched_.push_back(cell);
      list.push_back(index);
    }
}

bool Reservations::blocks(int self, const MotionLibrary& library, int segment,
                          const Placement& start) const {
  if (runs_.empty()) return false;
  thread_local std::vector<Reserved> placed;  // the candidate's frames; capacity kept
  placed.clear();
  vec2 lo, hi;
  place_frames(library.volumes(segment), 0, start, placed, lo, hi);
  if (placed.empty()) return false;
  lo -= vec2(clearance_m_ + kSlack_m);
  hi += vec2(clearance_m_ + kSlack_m);
  for (int z = cell_z(lo.y), z1 = cell_z(hi.y); z <= z1; ++z)
    for (int x = cell_x(lo.x), x1 = cell_x(hi.x); x <= x1; ++x)
      for (int i : cells_[static_cast<size_t>(z * count_x_ + x)]) {
        const Run& run = runs_[static_cast<size_t>(i)];
        if (run.owner == self || run.hi_m.x < lo.x || run.lo_m.x > hi.x || run.hi_m.y < lo.y || run.lo_m.y > hi.y)
          continue;
        // A run in several of these cells is looked at once: in the cell of the overlap's low corner.
        if (cell_x(std::max(run.lo_m.x, lo.x)) != x || cell_z(std::max(run.lo_m.y, lo.y)) != z) continue;
        if (run_blocks(run, placed)) return true;
      }
  return false;
}

bool Reservations::run_blocks(const Run& run, std::span<const Reserved> frames) const {
  for (const Reserved& a : frames) {
    const float reach = a.reach_m + clearance_m_ + kSlack_m;
    const vec2 c = a.volume.center_m;
    if (c.x + reach < run.lo_m.x || c.x - reach > run.hi_m.x || c.y + reach < run.lo_m.y || c.y - reach > run.hi_m.y)
      continue;
    for (int j = run.first; j < run.end; ++j) {
      const Reserved& b = bodies_[static_cast<size_t>(j)];
      const vec2 d = c - b.volume.center_m;
      const float r = reach + b.reach_m;
      if (glm::dot(d, d) < r * r && footprints_overlap(a.volume, b.volume, clearance_m_)) return true;
    }
  }
  return false;
}

}  // namespace foresight

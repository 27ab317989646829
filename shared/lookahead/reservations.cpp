#include "lookahead/reservations.hpp"

#include <algorithm>
#include <cmath>

namespace foresight {

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
  max_reach_m_ = 0.0f;
}

void Reservations::clear() {
  for (int c : touched_) cells_[static_cast<size_t>(c)].clear();
  touched_.clear();
  bodies_.clear();
  max_reach_m_ = 0.0f;
}

int Reservations::cell_of(vec2 p) const {
  const int ix = std::clamp(static_cast<int>(std::floor((p.x - origin_m_.x) / cell_m_)), 0, count_x_ - 1);
  const int iz = std::clamp(static_cast<int>(std::floor((p.y - origin_m_.y) / cell_m_)), 0, count_z_ - 1);
  return iz * count_x_ + ix;
}

void Reservations::add(int owner, const MotionLibrary& library, int segment, int from_frame,
                       const Placement& start) {
  const auto frames = library.volumes(segment);
  for (size_t f = static_cast<size_t>(std::max(from_frame, 0)); f < frames.size(); ++f) {
    const BodyVolume v = place(frames[f], start);
    const int cell = cell_of(v.center_m);
    auto& list = cells_[static_cast<size_t>(cell)];
    if (list.empty()) touched_.push_back(cell);
    list.push_back(static_cast<int>(bodies_.size()));
    bodies_.push_back({v, owner});
    max_reach_m_ = std::max(max_reach_m_, v.reach_m());
  }
}

bool Reservations::blocks(int self, const MotionLibrary& library, int segment,
                          const Placement& start) const {
  if (bodies_.empty()) return false;
  for (const BodyVolume& local : library.volumes(segment)) {
    const BodyVolume v = place(local, start);
    const float reach = v.reach_m() + max_reach_m_ + clearance_m_;
    const int x0 = cell_of(v.center_m - vec2(reach)) % count_x_, z0 = cell_of(v.center_m - vec2(reach)) / count_x_;
    const int x1 = cell_of(v.center_m + vec2(reach)) % count_x_, z1 = cell_of(v.center_m + vec2(reach)) / count_x_;
    for (int z = z0; z <= z1; ++z)
      for (int x = x0; x <= x1; ++x)
        for (int i : cells_[static_cast<size_t>(z * count_x_ + x)]) {
          const Reserved& d = bodies_[static_cast<size_t>(i)];
          if (d.owner != self && footprints_overlap(v, d.volume, clearance_m_)) return true;
        }
  }
  return false;
}

}  // namespace foresight

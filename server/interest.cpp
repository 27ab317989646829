#include "interest.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

namespace foresight::server {

void InterestGrid::build(std::span<const vec2> positions, float cell_m) {
  positions_ = positions;
  cell_m_ = cell_m > 0.0f ? cell_m : 1.0f;
  scratch_.clear();
  for (uint32_t i = 0; i < positions.size(); ++i) {
    const vec2 p = positions[i] / cell_m_;
    scratch_.push_back({key(static_cast<int>(std::floor(p.x)), static_cast<int>(std::floor(p.y))), i});
  }
  std::sort(scratch_.begin(), scratch_.end());
  order_.clear();
  ordered_.clear();
  cells_.clear();
  for (const auto& [k, i] : scratch_) {
    if (cells_.empty() || cells_.back().first != k) cells_.push_back({k, static_cast<uint32_t>(order_.size())});
    order_.push_back(i);
    ordered_.push_back(positions[i]);
  }
}

void InterestGrid::near(vec2 at, float radius_m, std::vector<uint32_t>& out) const {
  const vec2 c = at / cell_m_;
  const int cx = static_cast<int>(std::floor(c.x)), cz = static_cast<int>(std::floor(c.y));
  const float r2 = radius_m * radius_m;
  const int rings = std::max(1, static_cast<int>(std::ceil(radius_m / cell_m_)));
  thread_local std::vector<uint64_t> marks;  // a bit per position; capacity kept
  marks.assign((positions_.size() + 63) / 64, 0);
  for (int dz = -rings; dz <= rings; ++dz)
    for (int dx = -rings; dx <= rings; ++dx) {
      const int64_t k = key(cx + dx, cz + dz);
      const auto it = std::lower_bound(cells_.begin(), cells_.end(), std::pair<int64_t, uint32_t>{k, 0});
      if (it == cells_.end() || it->first != k) continue;
      const uint32_t end = it + 1 == cells_.end() ? static_cast<uint32_t>(order_.size()) : (it + 1)->second;
      for (uint32_t j = it->second; j < end; ++j) {
        const vec2 d = ordered_[j] - at;
        if (glm::dot(d, d) <= r2) marks[order_[j] / 64] |= uint64_t{1} << (order_[j] % 64);
      }
    }
  for (size_t w = 0; w < marks.size(); ++w)
    for (uint64_t bits = marks[w]; bits != 0; bits &= bits - 1)
      out.push_back(static_cast<uint32_t>(w * 64 + static_cast<size_t>(std::countr_zero(bits))));
}

void select_interest(const InterestGrid& grid, std::span<const vec2> positions, uint32_t own, float radius_m,
                     bool far_due, float far_radius_m, std::vector<uint32_t>& out, std::vector<uint8_t>& far) {
  out.clear();
  far.clear();
  if (far_due) {
    if (far_radius_m > radius_m) {
      grid.near(positions[own], far_radius_m, out);
    } else {
      for (uint32_t i = 0; i < positions.size(); ++i) out.push_back(i);  // everyone
    }
    // Mark who is far.
    const float r2 = radius_m * radius_m;
    for (uint32_t i : out) {
      const vec2 d = positions[i] - positions[own];
      far.push_back(i != own && glm::dot(d, d) > r2);
    }
    return;
  }
  grid.near(positions[own], radius_m, out);  // includes own
  far.assign(out.size(), 0);
}

}  // namespace foresight::server

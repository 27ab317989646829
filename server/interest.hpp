#pragma once
// Interest management (issue 8, docs/SERVER.md "Interest management"): which avatars go into one
// client's snapshot. Avatars within interest_radius_m of the client's own avatar go in every
// snapshot; the others only in every far_every-th one (0: never), and beyond far_radius_m (if set)
// not at all; staggered by client so the far avatars' bytes spread over the snapshots. A uniform
// grid with cells of the radius finds the near ones in the 3 x 3 cells around the client (and
// those within far_radius_m in the cells that far); the grid is rebuilt once per snapshot (no
// allocation once its vectors have grown).
#include "math/types.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace foresight::server {

class InterestGrid {
 public:
  /// Buckets `positions` (ground x, z) into cells of `cell_m` (> 0).
  void build(std::span<const vec2> positions, float cell_m);
  /// Appends to `out` the indices of the positions within radius_m of `at`, in ascending order.
  /// Looks at the cells within radius_m (3 x 3 when radius_m <= cell_m); the order comes from a
  /// bit per position (a thousand avatars: 16 words to clear and scan), not a sort.
  void near(vec2 at, float radius_m, std::vector<uint32_t>& out) const;

 private:
  int64_t key(int ix, int iz) const { return (static_cast<int64_t>(ix) << 32) ^ static_cast<uint32_t>(iz); }
  float cell_m_ = 1.0f;
  std::span<const vec2> positions_;
  // Cells sorted by key; each holds a run of `order_` (indices into positions).
  std::vector<std::pair<int64_t, uint32_t>> cells_;  ///< (key, first index into order_)
  std::vector<uint32_t> order_;
  std::vector<vec2> ordered_;  ///< positions_[order_[j]], contiguous for the distance tests.
  std::vector<std::pair<int64_t, uint32_t>> scratch_;
};

/// The avatars one client gets in this snapshot, as indices into `positions` in ascending order
/// (the snapshot's avatar order): `own` always; within `radius_m` always; when `far_due` the rest
/// within `far_radius_m` (everyone if it is not larger than radius_m). `far[k]` (one per entry of
/// `out`, so the work is the view's, not the world's) is set for out[k] beyond radius_m (the client
/// then knows they come less often).
void select_interest(const InterestGrid& grid, std::span<const vec2> positions, uint32_t own, float radius_m,
                     bool far_due, float far_radius_m, std::vector<uint32_t>& out, std::vector<uint8_t>& far);

}  // namespace foresight::server

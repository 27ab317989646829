#pragma once
// Per-segment precomputation for collision checks: a motion segment's per-frame body volumes in
// segment-local space (the segment starts at the origin facing +Z), stored contiguously in the
// order the check visits them, plus a bounding disc of the whole sweep for a one-lookup early-out.
// Built offline (when the motion library is compiled); checked millions of times per second.
#include "world/body_volume.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace foresight {

/// The order segment_feasible visits frames. Any order gives the same answer; a good one finds a
/// collision sooner. Start placements are usually free (they are the end of a feasible segment),
/// so collisions cluster at the end of the sweep, furthest from the start.
enum class FrameOrder : std::uint8_t {
  kSequential,    ///< 0, 1, ..., n-1.
  kLastFirst,     ///< n-1, then 0, 1, ..., n-2.
  kCoarseToFine,  ///< n-1, n-1-s, n-1-2s, ... (s = coarse stride), then the rest in order.
};
inline constexpr FrameOrder kDefaultFrameOrder = FrameOrder::kCoarseToFine;
inline constexpr int kDefaultCoarseStride = 8;

struct SegmentCollisionShape {
  std::vector<BodyVolume> frames;        ///< Segment-local, in time order.
  std::vector<BodyVolume> check_frames;  ///< The same frames in check order (hot).
  FrameOrder order = kDefaultFrameOrder;
  /// A disc containing every frame's footprint and the origin (the start point), segment-local.
  vec2 sweep_center_m{0.0f};
  float sweep_radius_m = 0.0f;
  float max_reach_m = 0.0f;  ///< Largest BodyVolume::reach_m() of a frame.
  float y_min_m = 0.0f;       ///< Lowest y_min over the frames.
  float y_max_m = 0.0f;       ///< Highest y_max over the frames.

  bool empty() const { return frames.empty(); }
};

/// Builds the shape. Sanitises bad frames instead of trusting them: a negative radius becomes 0,
/// swapped y bounds are swapped back, and a frame with a non-finite value always collides.
SegmentCollisionShape make_segment_shape(std::span<const BodyVolume> frames_local,
                                         FrameOrder order = kDefaultFrameOrder,
                                         int coarse_stride = kDefaultCoarseStride);

}  // namespace foresight

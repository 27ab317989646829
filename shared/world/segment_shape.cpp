#include "world/segment_shape.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace foresight {
namespace {

bool finite(const BodyVolume& v) {
  return std::isfinite(v.center_m.x) && std::isfinite(v.center_m.y) && std::isfinite(v.radius_m) &&
         std::isfinite(v.half_axis_m.x) && std::isfinite(v.half_axis_m.y) && std::isfinite(v.y_min_m) && std::isfinite(v.y_max_m);
}

BodyVolume sanitised(BodyVolume v) {
  if (!finite(v)) {
    // A NaN centre fails the bounds test of every check, so the frame always collides, and the
    // NaN spreads into the sweep disc, which disables the early-out.
    const float nan = std::numeric_limits<float>::quiet_NaN();
    return {vec2(nan), 0.0f, 0.0f, 0.0f};
  }
  v.radius_m = std::max(v.radius_m, 0.0f);
  if (v.y_min_m > v.y_max_m) std::swap(v.y_min_m, v.y_max_m);
  return v;
}

std::vector<int> check_order(int n, FrameOrder order, int stride) {
  std::vector<int> idx;
  idx.reserve(static_cast<std::size_t>(n));
  if (n == 0) return idx;
  std::vector<bool> taken(static_cast<std::size_t>(n), false);
  const auto take = [&](int i) {
    if (!taken[static_cast<std::size_t>(i)]) {
      taken[static_cast<std::size_t>(i)] = true;
      idx.push_back(i);
    }
  };
  switch (order) {
    case FrameOrder::kSequential: break;
    case FrameOrder::kLastFirst: take(n - 1); break;
    case FrameOrder::kCoarseToFine:
      for (int i = n - 1; i >= 0; i -= std::max(stride, 1)) take(i);
      break;
  }
  for (int i = 0; i < n; ++i) take(i);
  return idx;
}

}  // namespace

SegmentCollisionShape make_segment_shape(std::span<const BodyVolume> frames_local, FrameOrder order,
                                         int coarse_stride) {
  SegmentCollisionShape s;
  s.order = order;
  s.frames.reserve(frames_local.size());
  for (const BodyVolume& v : frames_local) s.frames.push_back(sanitised(v));
  const int n = static_cast<int>(s.frames.size());
  for (int i : check_order(n, order, coarse_stride)) s.check_frames.push_back(s.frames[i]);
  if (n == 0) return s;

  // Bounding box of all footprints and the origin; its centre is a good enough disc centre.
  vec2 lo(0.0f), hi(0.0f);
  s.y_min_m = s.frames[0].y_min_m;
  s.y_max_m = s.frames[0].y_max_m;
  for (const BodyVolume& v : s.frames) {
    const vec2 extent = glm::abs(v.half_axis_m) + vec2(v.radius_m);
    lo = glm::min(lo, v.center_m - extent);
    hi = glm::max(hi, v.center_m + extent);
    s.max_reach_m = std::max(s.max_reach_m, v.reach_m());
    s.y_min_m = std::min(s.y_min_m, v.y_min_m);
    s.y_max_m = std::max(s.y_max_m, v.y_max_m);
  }
  s.sweep_center_m = 0.5f * (lo + hi);
  float r = glm::length(s.sweep_center_m);  // The origin must be inside: see segment_feasible.
  for (const BodyVolume& v : s.frames)
    r = std::max(r, glm::length(v.center_m - s.sweep_center_m) + v.reach_m());
  s.sweep_radius_m = r;
  // A NaN frame makes the sweep NaN on purpose (no early-out); glm::min/max may drop NaN, so
  // restore it explicitly.
  for (const BodyVolume& v : s.frames) {
    if (std::isnan(v.center_m.x)) {
      s.sweep_center_m = vec2(std::numeric_limits<float>::quiet_NaN());
      s.sweep_radius_m = std::numeric_limits<float>::quiet_NaN();
      break;
    }
  }
  return s;
}

}  // namespace foresight

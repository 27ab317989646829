#pragma once
// What a pop is, for tests that watch poses frame by frame: the second difference of a joint's
// positions over three frames (m/frame^2), as the bench's motion-quality measure counts it.
#include "math/types.hpp"

#include <algorithm>
#include <cstddef>
#include <span>

namespace foresight::test {

/// The largest acceleration of joints [first, last) on the frame `now`, between `before` and
/// `after` (the same joints, one frame apart).
inline float largest_joint_acceleration(std::span<const vec3> before, std::span<const vec3> now,
                                        std::span<const vec3> after, size_t first = 0,
                                        size_t last = static_cast<size_t>(-1)) {
  float largest = 0.0f;
  for (size_t j = first; j < std::min(last, now.size()); ++j)
    largest = std::max(largest, glm::length(after[j] - 2.0f * now[j] + before[j]));
  return largest;
}

}  // namespace foresight::test

#pragma once
// A skeleton as flat arrays in depth-first order: parents[i] < i, so forward kinematics is one
// loop running forwards (ozz's layout). Joint 0 is the root (the pelvis once a clip is
// normalised: see bvh_import.hpp).
#include "math/types.hpp"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace foresight {

inline constexpr int16_t kNoParent = -1;

struct Skeleton {
  std::vector<std::string> joint_names;
  std::vector<int16_t> parents;         ///< parents[0] == kNoParent; parents[i] < i otherwise.
  std::vector<vec3> rest_offsets_m;     ///< Offset from the parent joint, parent space, metres.
  std::vector<bool> is_end_site;        ///< BVH End Site leaves (no channels, kept for drawing).

  int num_joints() const { return static_cast<int>(parents.size()); }
  /// Index of the joint called `name`, or -1.
  int find_joint(std::string_view name) const;
  /// True when the arrays are consistent (sizes equal, parents sorted, one root).
  bool valid() const;
};

}  // namespace foresight

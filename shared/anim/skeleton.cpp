#include "anim/skeleton.hpp"

namespace foresight {

int Skeleton::find_joint(std::string_view name) const {
  for (size_t i = 0; i < joint_names.size(); ++i)
    if (joint_names[i] == name) return static_cast<int>(i);
  return -1;
}

bool Skeleton::valid() const {
  const size_t n = parents.size();
  if (n == 0 || joint_names.size() != n || rest_offsets_m.size() != n || is_end_site.size() != n)
    return false;
  if (parents[0] != kNoParent) return false;
  for (size_t i = 1; i < n; ++i)
    if (parents[i] < 0 || static_cast<size_t>(parents[i]) >= i) return false;
  return true;
}

}  // namespace foresight

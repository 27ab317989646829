#include "anim/fk.hpp"

#include <cassert>

namespace foresight {

void fk_pose(const Skeleton& skeleton, std::span<const vec3> local_pos_m,
             std::span<const quat> local_rot, std::span<vec3> global_pos_m,
             std::span<quat> global_rot) {
  const int n = skeleton.num_joints();
  assert(static_cast<int>(local_pos_m.size()) >= n && static_cast<int>(local_rot.size()) >= n);
  assert(static_cast<int>(global_pos_m.size()) >= n && static_cast<int>(global_rot.size()) >= n);
  global_pos_m[0] = local_pos_m[0];
  global_rot[0] = local_rot[0];
  for (int j = 1; j < n; ++j) {
    const int p = skeleton.parents[j];
    // Sorted parents make this a single forward pass.
    assert(p >= 0 && p < j);
    global_pos_m[j] = global_pos_m[p] + global_rot[p] * local_pos_m[j];
    global_rot[j] = global_rot[p] * local_rot[j];
  }
}

void fk_clip_positions(const Skeleton& skeleton, const Clip& clip, std::vector<vec3>& global_pos_m) {
  const int n = skeleton.num_joints();
  assert(clip.num_joints == n);
  global_pos_m.resize(static_cast<size_t>(clip.num_frames) * n);
  std::vector<quat> rot(static_cast<size_t>(n));
  for (int f = 0; f < clip.num_frames; ++f) {
    fk_pose(skeleton, clip.frame_pos(f), clip.frame_rot(f),
            {global_pos_m.data() + static_cast<size_t>(f) * n, static_cast<size_t>(n)}, rot);
  }
}

}  // namespace foresight

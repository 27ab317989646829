#include "anim/clip.hpp"

namespace foresight {

void Clip::resize(const Skeleton& skeleton, int frames) {
  num_frames = frames;
  num_joints = skeleton.num_joints();
  const size_t n = static_cast<size_t>(frames) * static_cast<size_t>(num_joints);
  local_pos_m.resize(n);
  local_rot.assign(n, quat(1.0f, 0.0f, 0.0f, 0.0f));
  for (int f = 0; f < frames; ++f)
    for (int j = 0; j < num_joints; ++j)
      local_pos_m[static_cast<size_t>(f) * num_joints + j] = skeleton.rest_offsets_m[j];
}

}  // namespace foresight

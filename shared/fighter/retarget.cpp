#include "fighter/retarget.hpp"

#include <algorithm>
#include <cassert>

namespace foresight {

void PoseBuffers::resize(int num_joints) {
  const size_t n = static_cast<size_t>(num_joints);
  local_pos_m.resize(n);
  global_pos_m.resize(n);
  local_rot.resize(n);
  global_rot.resize(n);
}

void retarget_pose(const LimbCharacter& src, std::span<const vec3> local_pos_m,
                   std::span<const quat> local_rot, const Placement& src_root,
                   const LimbCharacter& dst, const Placement& dst_root, const PoseSpans& out) {
  assert(src.skeleton && src.model && dst.skeleton && dst.model);
  LimbPose limb;
  limb_pose_encode(*src.skeleton, *src.model, local_pos_m, local_rot, src_root, limb);
  limb_pose_decode(*dst.skeleton, *dst.model, limb, dst_root, out);
}

void retarget_clip_frame(const LimbCharacter& src, const Clip& clip, int frame,
                         const LimbCharacter& dst, const Placement& alignment, const PoseSpans& out) {
  assert(frame >= 0 && frame < clip.num_frames);
  retarget_pose(src, clip.frame_pos(frame), clip.frame_rot(frame), Placement{}, dst, alignment, out);
}

void retarget_clip(const LimbCharacter& src, const Clip& clip, const LimbCharacter& dst, Clip& out) {
  out.name = clip.name;
  out.fps = clip.fps;
  out.resize(*dst.skeleton, clip.num_frames);
  PoseBuffers buffers;
  buffers.resize(dst.skeleton->num_joints());
  for (int f = 0; f < clip.num_frames; ++f) {
    retarget_clip_frame(src, clip, f, dst, Placement{}, buffers.spans());
    std::copy(buffers.local_pos_m.begin(), buffers.local_pos_m.end(), out.frame_pos(f).begin());
    std::copy(buffers.local_rot.begin(), buffers.local_rot.end(), out.frame_rot(f).begin());
  }
}

}  // namespace foresight

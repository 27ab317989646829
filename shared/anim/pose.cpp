#include "anim/pose.hpp"

#include <algorithm>

namespace foresight {
namespace {

// Pelvis relative to the placement it stands on: the ground position and heading removed.
vec3 pelvis_pos_relative(vec3 pelvis, const Placement& root) {
  return root.inverse().apply(pelvis);
}
quat pelvis_rot_relative(quat pelvis, const Placement& root) {
  return quat_from_heading(-root.heading_rad) * pelvis;
}

}  // namespace

void pose_from_clip(const Clip& clip, int frame, const Placement& from, const Placement& to,
                    Pose& out) {
  out.resize(clip.num_joints);
  const auto pos = clip.frame_pos(frame);
  const auto rot = clip.frame_rot(frame);
  std::copy(pos.begin(), pos.end(), out.local_pos_m.begin());
  std::copy(rot.begin(), rot.end(), out.local_rot.begin());
  const Placement move = to.compose(from.inverse());
  out.local_pos_m[0] = move.apply(pos[0]);
  out.local_rot[0] = move.apply(rot[0]);
}

void pose_offset_between(const Clip& a_clip, int a_frame, const Placement& a_root,
                         const Clip& b_clip, int b_frame, const Placement& b_root, PoseOffset& out) {
  const int n = a_clip.num_joints;
  out.pos_m.resize(static_cast<size_t>(n));
  out.rot.resize(static_cast<size_t>(n));
  const auto ap = a_clip.frame_pos(a_frame), bp = b_clip.frame_pos(b_frame);
  const auto ar = a_clip.frame_rot(a_frame), br = b_clip.frame_rot(b_frame);
  out.pos_m[0] = pelvis_pos_relative(ap[0], a_root) - pelvis_pos_relative(bp[0], b_root);
  quat d = pelvis_rot_relative(ar[0], a_root) * glm::inverse(pelvis_rot_relative(br[0], b_root));
  out.rot[0] = d.w < 0.0f ? -d : d;
  for (int j = 1; j < n; ++j) {
    out.pos_m[j] = ap[j] - bp[j];
    d = ar[j] * glm::inverse(br[j]);
    // Shortest arc, so slerp from identity never takes the long way round.
    out.rot[j] = d.w < 0.0f ? -d : d;
  }
}

void pose_apply_offset(const PoseOffsetView& offset, float weight, const Placement& root, Pose& pose) {
  if (weight <= 0.0f) return;
  const quat identity(1.0f, 0.0f, 0.0f, 0.0f);
  const int n = static_cast<int>(pose.local_rot.size());
  // Pelvis: into root-relative space, add the offset, back to world.
  vec3 rel_pos = pelvis_pos_relative(pose.local_pos_m[0], root) + weight * offset.pos_m[0];
  quat rel_rot = glm::slerp(identity, offset.rot[0], weight) *
                 pelvis_rot_relative(pose.local_rot[0], root);
  pose.local_pos_m[0] = root.apply(rel_pos);
  pose.local_rot[0] = root.apply(rel_rot);
  for (int j = 1; j < n; ++j) {
    pose.local_pos_m[j] += weight * offset.pos_m[j];
    pose.local_rot[j] = glm::normalize(glm::slerp(identity, offset.rot[j], weight) * pose.local_rot[j]);
  }
}

float blend_out_weight(int k, int n) {
  if (n <= 0 || k >= n) return 0.0f;
  if (k <= 0) return 1.0f;
  const float t = static_cast<float>(k) / static_cast<float>(n);
  return 1.0f - t * t * (3.0f - 2.0f * t);
}

}  // namespace foresight

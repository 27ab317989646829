#pragma once
// One pose in flat arrays, and the root-relative split used to play and blend clips from any
// placement: the pelvis is expressed relative to the ground placement it stands on (its height
// and its rotation relative to the heading), every other joint stays parent-relative.
#include "anim/clip.hpp"

#include <span>
#include <vector>

namespace foresight {

struct Pose {
  std::vector<vec3> local_pos_m;  ///< Joint 0: pelvis in the pose's space; others parent-relative.
  std::vector<quat> local_rot;
  void resize(int num_joints) {
    local_pos_m.resize(static_cast<size_t>(num_joints));
    local_rot.resize(static_cast<size_t>(num_joints));
  }
};

/// Copies frame `frame` of `clip` with its pelvis moved from `from` (the frame's root placement
/// in clip space) to `to` (where it should stand, world space).
void pose_from_clip(const Clip& clip, int frame, const Placement& from, const Placement& to,
                    Pose& out);

/// The offset that carries pose `b` onto pose `a`, both expressed relative to their own root
/// placements (so only pelvis height/tilt and joint rotations differ, never ground position).
struct PoseOffset {
  std::vector<vec3> pos_m;  ///< a - b (pelvis only is non-zero unless translations differ).
  std::vector<quat> rot;    ///< a * inverse(b) per joint.
};
/// A PoseOffset stored elsewhere (e.g. precomputed per transition in a flat array).
struct PoseOffsetView {
  std::span<const vec3> pos_m;
  std::span<const quat> rot;
};
void pose_offset_between(const Clip& a_clip, int a_frame, const Placement& a_root,
                         const Clip& b_clip, int b_frame, const Placement& b_root, PoseOffset& out);

/// Applies `weight` (1 = all of it, 0 = none) of an offset to a pose placed at `root` (the pose's
/// own root placement, world space). Used to blend a transition out over its blend frames.
void pose_apply_offset(const PoseOffsetView& offset, float weight, const Placement& root, Pose& pose);

/// Smooth blend-out weight for frame k of an n-frame blend: 1 at k = 0, 0 at k >= n, zero slope
/// at both ends (so the blend adds no velocity jump of its own).
float blend_out_weight(int k, int n);

}  // namespace foresight

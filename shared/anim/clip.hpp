#pragma once
// A clip: normalised motion (metres, Y up, 30 or 60 fps) on a Skeleton, stored as two
// contiguous frame-major arrays. Local translations are kept per frame (not only the rest
// offsets) because BVH allows position channels on any joint.
#include "anim/skeleton.hpp"

#include <span>
#include <string>
#include <vector>

namespace foresight {

struct Clip {
  std::string name;
  float fps = 30.0f;
  int num_frames = 0;
  int num_joints = 0;
  /// [frame * num_joints + joint]: translation relative to the parent joint, metres. For joint 0
  /// (the pelvis) this is its position in clip space.
  std::vector<vec3> local_pos_m;
  /// [frame * num_joints + joint]: rotation relative to the parent joint (joint 0: clip space).
  std::vector<quat> local_rot;

  float duration_s() const { return num_frames > 1 ? (num_frames - 1) / fps : 0.0f; }
  std::span<const vec3> frame_pos(int frame) const {
    return {local_pos_m.data() + static_cast<size_t>(frame) * num_joints,
            static_cast<size_t>(num_joints)};
  }
  std::span<const quat> frame_rot(int frame) const {
    return {local_rot.data() + static_cast<size_t>(frame) * num_joints,
            static_cast<size_t>(num_joints)};
  }
  std::span<vec3> frame_pos(int frame) {
    return {local_pos_m.data() + static_cast<size_t>(frame) * num_joints,
            static_cast<size_t>(num_joints)};
  }
  std::span<quat> frame_rot(int frame) {
    return {local_rot.data() + static_cast<size_t>(frame) * num_joints,
            static_cast<size_t>(num_joints)};
  }
  /// Allocates num_frames x num_joints frames, rest pose (skeleton offsets, identity rotations).
  void resize(const Skeleton& skeleton, int frames);
};

}  // namespace foresight

#pragma once
// Forward kinematics over the flat skeleton arrays.
#include "anim/clip.hpp"

#include <span>

namespace foresight {

/// Model-space (clip-space) joint positions and rotations of one pose.
/// Inputs are local (parent-space) translations and rotations; outputs have num_joints entries.
void fk_pose(const Skeleton& skeleton, std::span<const vec3> local_pos_m,
             std::span<const quat> local_rot, std::span<vec3> global_pos_m,
             std::span<quat> global_rot);

/// Joint positions of every frame of a clip, [frame * num_joints + joint], clip space.
/// `global_pos_m` is resized once; pass the same vector again to reuse its storage.
void fk_clip_positions(const Skeleton& skeleton, const Clip& clip, std::vector<vec3>& global_pos_m);

}  // namespace foresight

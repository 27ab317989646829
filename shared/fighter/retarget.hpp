#pragma once
// Retargeting (paper 3.4.1): a pose or a clip from its source skeleton (the default library's, a
// Bandai mocap skeleton, any skeleton with a LimbModel) onto another skeleton (a fighter
// morphology), through the morphology-independent LimbPose: encode on the source, decode on the
// target. Grounded feet stay on the ground and planted feet stay planted (the representation keeps
// the contact joint's clearance and ground position in leg lengths; see limb_representation.hpp).
#include "fighter/limb_representation.hpp"

#include <vector>

namespace foresight {

/// A skeleton with its model (both owned elsewhere, outliving the view).
struct LimbCharacter {
  const Skeleton* skeleton = nullptr;
  const LimbModel* model = nullptr;
};

/// Pose storage for one skeleton, sized once (then every retarget into it is allocation-free).
struct PoseBuffers {
  std::vector<vec3> local_pos_m, global_pos_m;
  std::vector<quat> local_rot, global_rot;
  void resize(int num_joints);
  PoseSpans spans() { return {local_pos_m, local_rot, global_pos_m, global_rot}; }
};

/// One pose: `src_root` is the source pose's ground placement (in the pose's own space), `dst_root`
/// where the target should stand (world). No allocation.
void retarget_pose(const LimbCharacter& src, std::span<const vec3> local_pos_m,
                   std::span<const quat> local_rot, const Placement& src_root,
                   const LimbCharacter& dst, const Placement& dst_root, const PoseSpans& out);

/// Frame `frame` of a clip, the clip's space mapped by `alignment` (clip space -> world). No
/// allocation.
void retarget_clip_frame(const LimbCharacter& src, const Clip& clip, int frame,
                         const LimbCharacter& dst, const Placement& alignment, const PoseSpans& out);

/// A whole clip, kept in clip space (offline: allocates `out` once). Same name, fps, frame count.
void retarget_clip(const LimbCharacter& src, const Clip& clip, const LimbCharacter& dst, Clip& out);

}  // namespace foresight

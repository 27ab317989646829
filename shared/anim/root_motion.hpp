#pragma once
// Root motion: the pelvis (joint 0) trajectory split into a ground-plane placement (position on the
// floor + heading) and the rest (pelvis height and rotation relative to that placement), so a clip
// can be played from any placement.
#include "anim/clip.hpp"

#include <vector>

namespace foresight {

/// Indices of a left/right joint pair high in the hierarchy (upper legs, else shoulders), found by
/// name ("Left"/"Right", "_L"/"_R", "L_"/"R_", ".l"/".r", case-insensitive). {-1, -1} if none.
struct LeftRightPair {
  int left = -1;
  int right = -1;
};
LeftRightPair find_left_right_pair(const Skeleton& skeleton);

/// Index of the joint that mirrors `joint` (LeftHand <-> RightHand), or `joint` itself.
int mirror_joint(const Skeleton& skeleton, int joint);

/// The pelvis axis, in pelvis-local space, that points forward (the facing direction).
/// Found from frame 0: forward = (left - right) x up for the left/right pair, projected on the
/// ground; without a pair, the direction the pelvis travels over the clip (or +Z if it stays).
vec3 find_forward_axis(const Skeleton& skeleton, const Clip& clip);

/// Per frame, where the avatar stands on the ground (pelvis projected) and which way it faces.
void extract_root_track(const Clip& clip, vec3 forward_axis_local, std::vector<Placement>& track);

}  // namespace foresight

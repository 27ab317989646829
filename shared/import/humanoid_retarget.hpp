#pragma once
// Captured motion onto the canonical skeleton (canonical_skeleton.hpp), whatever the capture's
// hierarchy, naming or rest pose.
//
// Each frame, the capture's joints give the canonical joints' positions (the spine's inner joints
// are points at fixed arc fractions along the capture's pelvis-to-chest chain; a missing clavicle,
// toe or end point is placed from its neighbours). Each canonical joint then gets the rotation
// that aims its bone where the capture's bone points, with the twist taken from the body's own
// left/up/forward at that joint (never from the capture's rest pose, which may be a T-pose, an
// A-pose or, as in the Bandai set, lying on its side). Positions are therefore exact wherever the
// canonical bone lengths are the capture's; twist inside a limb is not reproduced.
#include "anim/canonical_skeleton.hpp"
#include "anim/clip.hpp"
#include "import/humanoid_map.hpp"

#include <span>

namespace foresight {

/// The canonical skeleton with the proportions of the mapped capture: bone lengths, hip and
/// shoulder placement measured in `positions` (one frame of global positions, Y up, metres:
/// the tallest frame reads the bones straightest). Directions of the limb bones stay canonical.
Skeleton canonical_skeleton_from_capture(const HumanoidMap& map, std::span<const vec3> positions);

/// The map of the canonical skeleton onto itself (to retarget between two canonical bodies).
HumanoidMap canonical_humanoid_map();

/// Hip-to-ankle length of a canonical skeleton (the mean of both legs).
float canonical_leg_length(const Skeleton& canonical);

/// Retargets `clip` (on `source`) onto `canonical`. The pelvis path is scaled by `root_scale`
/// (the target's leg length over the capture's, so a longer-legged body strides further).
void retarget_to_canonical(const Skeleton& source, const Clip& clip, const HumanoidMap& map,
                           const Skeleton& canonical, float root_scale, Clip& out);

}  // namespace foresight

#pragma once
// The default library's humanoid skeleton (owned by the procedural authoring code).
#include "anim/skeleton.hpp"

namespace foresight::author {

/// The one skeleton every default clip uses: 27 joints (22 animated + 5 End Sites), metres, Y up,
/// facing +Z, the character's left is +X. Rest pose: standing upright, arms hanging straight down,
/// feet flat (ankles 8 cm, balls of the feet 2.5 cm above the floor), head top at 1.75 m.
/// Limb bones point straight down (-Y) in the rest pose: the two-bone IK relies on it.
///   Hips(root) Spine Spine1 Chest Neck Head HeadTop_End
///   {Left,Right}Shoulder Arm ForeArm Hand Hand_End          (Shoulder = clavicle, Arm = shoulder joint)
///   {Left,Right}UpLeg Leg Foot ToeBase Toe_End             (UpLeg = hip joint, Foot = ankle)
Skeleton default_skeleton();

/// Rest-pose dimensions, shared by the skeleton and the authoring code.
inline constexpr float kRestPelvisHeightM = 0.97f;
inline constexpr float kRestAnkleHeightM = 0.08f;
inline constexpr float kRestBallHeightM = 0.025f;  ///< ToeBase joint; the sole is on the floor.

}  // namespace foresight::author

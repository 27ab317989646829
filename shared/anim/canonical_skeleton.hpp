#pragma once
// Foresight's one humanoid skeleton. Every library plays on it: the default library's clips are
// authored on it, and captured clips of any skeleton are retargeted onto it (humanoid_retarget.hpp),
// so fighters, collision volumes and the client find the same joints by the same indices whatever
// the capture's naming or hierarchy.
//
// 27 joints (22 animated + 5 End Sites), metres, Y up, facing +Z, the character's left is +X.
// Rest pose: standing upright, arms hanging straight down, feet flat, every rotation identity.
// Limb bones point straight down (-Y) in the rest pose: two-bone IK relies on it.
//   Hips(root) Spine Spine1 Chest Neck Head HeadTop_End
//   {Left,Right}Shoulder Arm ForeArm Hand Hand_End          (Shoulder = clavicle, Arm = shoulder joint)
//   {Left,Right}UpLeg Leg Foot ToeBase Toe_End             (UpLeg = hip joint, Foot = ankle)
#include "anim/skeleton.hpp"

namespace foresight {

/// Rest-pose heights of the built-in proportions (the authoring code builds on them).
inline constexpr float kRestPelvisHeightM = 0.97f;
inline constexpr float kRestAnkleHeightM = 0.08f;
inline constexpr float kRestBallHeightM = 0.025f;  ///< ToeBase joint; the sole is on the floor.

/// Joint indices of the canonical skeleton (depth-first order).
enum CanonicalJoint : int {
  kCanonHips, kCanonSpine, kCanonSpine1, kCanonChest, kCanonNeck, kCanonHead, kCanonHeadTop,
  kCanonLeftShoulder, kCanonLeftArm, kCanonLeftForeArm, kCanonLeftHand, kCanonLeftHandEnd,
  kCanonRightShoulder, kCanonRightArm, kCanonRightForeArm, kCanonRightHand, kCanonRightHandEnd,
  kCanonLeftUpLeg, kCanonLeftLeg, kCanonLeftFoot, kCanonLeftToeBase, kCanonLeftToeEnd,
  kCanonRightUpLeg, kCanonRightLeg, kCanonRightFoot, kCanonRightToeBase, kCanonRightToeEnd,
  kCanonJointCount
};

/// The canonical skeleton with the built-in proportions: a 1.75 m adult, leg 0.84 m hip to
/// ankle (thigh = shin), arm 0.54 m shoulder to wrist, shoulder joints 0.35 m apart at 1.43 m,
/// ankles 8 cm and balls of the feet 2.5 cm above the floor, head top at 1.75 m.
Skeleton canonical_skeleton();

/// The child whose direction a canonical joint's rotation aims (its bone), or -1 for End Sites.
int canonical_primary_child(int joint);

/// Standing height of the built-in proportions: head top above the balls of the feet (1.75 m -
/// 0.025 m). Import scales every captured body to it (bvh_import.hpp).
inline constexpr float kCanonicalStandingHeightM = 1.725f;
/// Hip -> knee -> ankle of the built-in proportions.
inline constexpr float kCanonicalLegLengthM = 0.84f;

}  // namespace foresight

#pragma once
// The joints a fighter needs (pelvis, spine, head, clavicles, arms, legs), found by name on any
// skeleton that follows one of the common naming schemes: the default library's (Mixamo/CMU:
// "LeftArm", "LeftForeArm", "LeftUpLeg"...) and the Bandai-Namco mocap set's ("UpperArm_L",
// "LowerArm_L", "UpperLeg_L"...). Sides are indexed 0 = left, 1 = right.
//
// Nothing here assumes a rest pose: the Bandai rest pose lies on its side, so sizes are bone
// lengths, never rest heights.
#include "anim/skeleton.hpp"

#include <array>
#include <string>
#include <vector>

namespace foresight {

inline constexpr int kFighterLeft = 0;
inline constexpr int kFighterRight = 1;

/// A two-bone chain root -> mid -> end: shoulder -> elbow -> wrist, or hip -> knee -> ankle.
struct FighterLimb {
  int root = -1, mid = -1, end = -1;
  float upper_m = 0.0f;  ///< |root -> mid|
  float lower_m = 0.0f;  ///< |mid -> end|
  float length_m() const { return upper_m + lower_m; }
};

struct FighterRig {
  int pelvis = -1;               ///< Joint 0 (the skeleton's root once imported).
  std::vector<int> spine;        ///< From the pelvis's child up to the chest (the neck's parent).
  int neck = -1;
  int head = -1;
  std::array<int, 2> clavicle{-1, -1};  ///< The arm root's parent (may be the chest).
  std::array<FighterLimb, 2> arm;
  std::array<FighterLimb, 2> leg;
  std::array<int, 2> toe{-1, -1};       ///< Ball of the foot; -1 when the skeleton has none.
  /// Size used to scale targets between characters (paper eq. 1): leg length plus the bone
  /// lengths from the pelvis up to the head. Not the standing height, but proportional to it
  /// for any skeleton measured the same way.
  float body_size_m = 0.0f;
};

/// Finds every role (case-insensitive names). False with a reason naming the missing role.
bool fighter_rig_from_skeleton(const Skeleton& skeleton, FighterRig& rig, std::string& error);

}  // namespace foresight

#pragma once
// Joint roles of the default skeleton, looked up once by name, with the bone lengths the
// authoring code needs (limb segments, foot geometry). Sides are indexed 0 = left, 1 = right.
#include "anim/skeleton.hpp"

#include <array>

namespace foresight::author {

inline constexpr int kLeft = 0;
inline constexpr int kRight = 1;
/// +1 for the left side (+X), -1 for the right side.
inline constexpr float side_sign(int side) { return side == kLeft ? 1.0f : -1.0f; }

/// A two-bone chain: root (hip/shoulder) -> mid (knee/elbow) -> end (ankle/wrist). Both bones
/// point along -Y in the rest pose.
struct LimbRig {
  int root = -1, mid = -1, end = -1;
  float upper_m = 0.0f, lower_m = 0.0f;
};

struct Rig {
  int hips = -1;
  std::array<int, 3> spine{-1, -1, -1};  ///< Spine, Spine1, Chest.
  int neck = -1, head = -1, head_top = -1;
  std::array<int, 2> clavicle{-1, -1};
  std::array<LimbRig, 2> arm;             ///< Arm, ForeArm, Hand.
  std::array<int, 2> hand_end{-1, -1};
  std::array<LimbRig, 2> leg;             ///< UpLeg, Leg, Foot.
  std::array<int, 2> toe{-1, -1};         ///< ToeBase (ball of the foot).
  std::array<int, 2> toe_end{-1, -1};
  vec3 ball_from_ankle_m{0.0f};           ///< ToeBase offset in the foot frame.
  vec3 toe_from_ball_m{0.0f};             ///< Toe_End offset in the toe frame.
  float ankle_height_m = 0.0f;            ///< Ankle above the floor with the foot flat.
};

/// Resolves the roles on a skeleton named like default_skeleton(); -1 entries if a name is missing.
Rig rig_from_skeleton(const Skeleton& skeleton);
/// True when every role was found and the limb bones point along -Y at rest.
bool rig_valid(const Skeleton& skeleton, const Rig& rig);

}  // namespace foresight::author

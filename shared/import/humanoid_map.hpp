#pragma once
// Which joint of a captured skeleton plays which part of a human body, found from the hierarchy
// and the posed geometry, never from names alone (studios name joints every way there is):
//  * the feet are the two lowest leaves of separate limbs; the pelvis is where their chains meet;
//  * the head is the highest leaf outside the legs; the spine is the chain from pelvis to head;
//  * the arms are the two longest chains that branch off the spine; the chest is where they branch;
//  * along each limb the hip/knee (shoulder/elbow) pair is the one whose two bones are most
//    nearly equal (thigh ~ shin, upper arm ~ forearm), so twist, roll and helper joints inside a
//    limb are skipped; the ankle is the top of the foot, the lowest long, upright bone's end;
//  * left is the side the body's left points to, the body facing where its toes point (or where
//    it travels); names decide only when the geometry cannot.
// Joints no role takes (fingers, face, twist and helper bones, props) are dropped by retargeting.
#include "anim/skeleton.hpp"

#include <array>
#include <span>
#include <string>
#include <vector>

namespace foresight {

struct HumanoidMap {
  int pelvis = -1;
  std::vector<int> spine;  ///< Joints strictly between the pelvis and the chest, pelvis side first.
  int chest = -1;          ///< Where the arms branch off.
  int neck = -1, head = -1;
  int head_top = -1;       ///< The head chain's leaf, or -1 when the head joint is the leaf.
  // Index 0 = left, 1 = right.
  std::array<int, 2> clavicle{-1, -1};  ///< -1 when the arm hangs straight off the chest.
  std::array<int, 2> upper_arm{-1, -1}, forearm{-1, -1}, hand{-1, -1};
  std::array<int, 2> hand_end{-1, -1};  ///< The hand chain's farthest leaf, or -1.
  std::array<int, 2> thigh{-1, -1}, shin{-1, -1}, foot{-1, -1};
  std::array<int, 2> toe{-1, -1}, toe_end{-1, -1};  ///< -1 when the chain ends at the ankle.
  bool sides_from_names = false;  ///< The geometry could not tell left from right.

  /// Every joint some role takes (spine included), by source index.
  std::vector<int> used_joints() const;
};

/// Finds the roles on `skeleton`, posed by `positions` ([frame * num_joints + joint], Y up, any
/// length unit, a few frames spread over a clip). False with a reason a person can act on
/// ("no two arms: ...") when the skeleton is not a usable humanoid.
bool humanoid_map_find(const Skeleton& skeleton, std::span<const vec3> positions,
                       HumanoidMap& out, std::string& error);

/// The highest head point above the lowest foot point, largest over the frames, in the
/// positions' unit: what a tape would read, but only as good as the rig's head end (many rigs end
/// the head chain at the skull's base), so reported, not scaled by.
float humanoid_head_height(const Skeleton& skeleton, const HumanoidMap& map,
                           std::span<const vec3> positions);

/// Standing height from the legs: hip -> knee -> ankle, both legs' mean, times the canonical
/// skeleton's height-to-leg ratio (1.725 / 0.84). Bone lengths do not change with the pose, so a
/// crouching or lying clip measures the same as a standing one, and the rig's head convention
/// does not matter. In the positions' unit.
float humanoid_stature(const HumanoidMap& map, std::span<const vec3> positions);

}  // namespace foresight

#include "author/default_skeleton.hpp"
#include "author/rig.hpp"
#include "anim/fk.hpp"
#include "anim/root_motion.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace foresight::author {
namespace {

std::vector<vec3> rest_positions(const Skeleton& s) {
  Clip clip;
  clip.resize(s, 1);
  std::vector<vec3> pos;
  fk_clip_positions(s, clip, pos);
  return pos;
}

TEST(DefaultSkeleton, IsValidWithTheNamedJoints) {
  const Skeleton s = default_skeleton();
  ASSERT_TRUE(s.valid());
  EXPECT_GE(s.num_joints(), 20);
  EXPECT_EQ(s.find_joint("Hips"), 0);
  for (const char* name :
       {"Spine", "Spine1", "Chest", "Neck", "Head", "LeftShoulder", "LeftArm", "LeftForeArm",
        "LeftHand", "RightShoulder", "RightArm", "RightForeArm", "RightHand", "LeftUpLeg",
        "LeftLeg", "LeftFoot", "LeftToeBase", "RightUpLeg", "RightLeg", "RightFoot",
        "RightToeBase"})
    EXPECT_GE(s.find_joint(name), 0) << name;
  int animated = 0;
  for (int j = 0; j < s.num_joints(); ++j) animated += s.is_end_site[j] ? 0 : 1;
  EXPECT_GE(animated, 20);
  EXPECT_TRUE(rig_valid(s, rig_from_skeleton(s)));
}

TEST(DefaultSkeleton, StandsOnTheFloorAtHumanHeight) {
  const Skeleton s = default_skeleton();
  const std::vector<vec3> pos = rest_positions(s);
  const float top = pos[s.find_joint("HeadTop_End")].y;
  EXPECT_GE(top, 1.6f);
  EXPECT_LE(top, 1.9f);
  float lowest = 10.0f;
  for (const vec3& p : pos) lowest = std::min(lowest, p.y);
  EXPECT_NEAR(lowest, kRestBallHeightM, 1e-5f);  // The balls of the feet, sole on the floor.
  EXPECT_NEAR(pos[s.find_joint("LeftFoot")].y, kRestAnkleHeightM, 1e-5f);
  // Left is +X, and the sides mirror each other.
  for (const char* name : {"Arm", "Hand", "UpLeg", "Foot", "ToeBase"}) {
    const vec3 l = pos[s.find_joint(std::string("Left") + name)];
    const vec3 r = pos[s.find_joint(std::string("Right") + name)];
    EXPECT_GT(l.x, 0.05f) << name;
    EXPECT_NEAR(l.x, -r.x, 1e-6f) << name;
    EXPECT_NEAR(l.y, r.y, 1e-6f) << name;
  }
  // Toes point forward (+Z).
  EXPECT_GT(pos[s.find_joint("LeftToeBase")].z, pos[s.find_joint("LeftFoot")].z + 0.1f);
}

TEST(DefaultSkeleton, RootMotionFindsTheHipsAndFacesPlusZ) {
  const Skeleton s = default_skeleton();
  const LeftRightPair pair = find_left_right_pair(s);
  EXPECT_EQ(pair.left, s.find_joint("LeftUpLeg"));
  EXPECT_EQ(pair.right, s.find_joint("RightUpLeg"));
  Clip clip;
  clip.resize(s, 2);
  const vec3 axis = find_forward_axis(s, clip);
  EXPECT_NEAR(axis.z, 1.0f, 1e-5f);
  EXPECT_EQ(mirror_joint(s, s.find_joint("LeftHand_End")), s.find_joint("RightHand_End"));
}

}  // namespace
}  // namespace foresight::author

#include "author/default_skeleton.hpp"
#include "import/bvh_import.hpp"
#include "fighter/fighter_rig.hpp"
#include "support/test_paths.hpp"

#include <gtest/gtest.h>

namespace foresight {
namespace {

TEST(FighterRig, FindsEveryRoleOnTheDefaultSkeleton) {
  const Skeleton s = author::default_skeleton();
  FighterRig rig;
  std::string error;
  ASSERT_TRUE(fighter_rig_from_skeleton(s, rig, error)) << error;
  EXPECT_EQ(s.joint_names[static_cast<size_t>(rig.arm[kFighterLeft].end)], "LeftHand");
  EXPECT_EQ(s.joint_names[static_cast<size_t>(rig.leg[kFighterRight].mid)], "RightLeg");
  EXPECT_EQ(s.joint_names[static_cast<size_t>(rig.clavicle[kFighterLeft])], "LeftShoulder");
  EXPECT_EQ(rig.spine.size(), 3u);  // Spine, Spine1, Chest
  // A 1.7-1.8 m default character: legs ~0.85 m, trunk to the head ~0.6 m.
  EXPECT_GT(rig.body_size_m, 1.2f);
  EXPECT_LT(rig.body_size_m, 1.8f);
}

TEST(FighterRig, FindsEveryRoleOnTheMocapSkeleton) {
  FORESIGHT_REQUIRE_MOCAP();
  Skeleton s;
  Clip clip;
  std::string error;
  ASSERT_TRUE(clip_load_bvh(test::mocap_dir() / "fighting" / "bandai_dataset-1_punch_normal_001.bvh", {}, s,
                            clip, nullptr, error)) << error;
  FighterRig rig;
  ASSERT_TRUE(fighter_rig_from_skeleton(s, rig, error)) << error;
  EXPECT_EQ(s.joint_names[static_cast<size_t>(rig.arm[kFighterLeft].root)], "UpperArm_L");
  EXPECT_EQ(s.joint_names[static_cast<size_t>(rig.leg[kFighterRight].end)], "Foot_R");
  EXPECT_EQ(s.joint_names[static_cast<size_t>(rig.clavicle[kFighterRight])], "Shoulder_R");
  EXPECT_GT(rig.body_size_m, 1.2f);
  EXPECT_LT(rig.body_size_m, 1.8f);
}

TEST(FighterRig, NamesTheMissingRole) {
  Skeleton s = author::default_skeleton();
  for (std::string& name : s.joint_names)
    if (name == "LeftForeArm") name = "Elbow";
  FighterRig rig;
  std::string error;
  EXPECT_FALSE(fighter_rig_from_skeleton(s, rig, error));
  EXPECT_NE(error.find("left arm"), std::string::npos) << error;
}

}  // namespace
}  // namespace foresight

#include "anim/fk.hpp"

#include <gtest/gtest.h>

namespace foresight {
namespace {

Skeleton chain3() {
  Skeleton s;
  s.joint_names = {"root", "mid", "tip"};
  s.parents = {kNoParent, 0, 1};
  s.rest_offsets_m = {vec3(0.0f), vec3(0, 1, 0), vec3(0, 1, 0)};
  s.is_end_site = {false, false, true};
  return s;
}

TEST(Fk, RotatedChainPlacesTipWhereHandComputationDoes) {
  const Skeleton s = chain3();
  ASSERT_TRUE(s.valid());
  Clip clip;
  clip.resize(s, 1);
  clip.frame_pos(0)[0] = vec3(1, 0, 0);
  clip.frame_rot(0)[1] = glm::angleAxis(kPi / 2, vec3(0, 0, 1));  // bend the mid joint
  std::vector<vec3> pos;
  fk_clip_positions(s, clip, pos);
  ASSERT_EQ(pos.size(), 3u);
  EXPECT_NEAR(pos[1].y, 1.0f, 1e-6f);
  // Rotating +Y by 90 degrees about +Z gives -X.
  EXPECT_NEAR(pos[2].x, 0.0f, 1e-6f);
  EXPECT_NEAR(pos[2].y, 1.0f, 1e-6f);
}

TEST(Skeleton, RejectsUnsortedParents) {
  Skeleton s = chain3();
  s.parents = {kNoParent, 2, 0};
  EXPECT_FALSE(s.valid());
}

}  // namespace
}  // namespace foresight

#include "author/default_skeleton.hpp"
#include "anim/fk.hpp"
#include "fighter/morphology.hpp"

#include <gtest/gtest.h>

#include <set>

namespace foresight {
namespace {

struct Proportions {
  float height, legs, arms, trunk;  // limbs and trunk as fractions of the height
};

Proportions proportions(const Morphology& m) {
  const FighterRig& r = m.rig;
  float trunk = 0.0f;
  for (int j = r.neck; j > 0; j = m.skeleton.parents[static_cast<size_t>(j)])
    trunk += glm::length(m.skeleton.rest_offsets_m[static_cast<size_t>(j)]);
  return {m.height_m, r.leg[0].length_m() / m.height_m, r.arm[0].length_m() / m.height_m, trunk / m.height_m};
}

TEST(Morphology, FiveCharactersDifferInHeightAndProportions) {
  const std::vector<Morphology> morphs = default_morphologies();
  ASSERT_EQ(morphs.size(), 5u);
  std::set<std::string> names;
  for (const Morphology& m : morphs) names.insert(m.name);
  EXPECT_EQ(names.size(), 5u);
  for (size_t a = 0; a < morphs.size(); ++a)
    for (size_t b = a + 1; b < morphs.size(); ++b) {
      const Proportions pa = proportions(morphs[a]), pb = proportions(morphs[b]);
      // Clearly different heights (at least 5 cm) ...
      EXPECT_GT(std::abs(pa.height - pb.height), 0.05f) << morphs[a].name << " / " << morphs[b].name;
      // ... and proportions: some limb or trunk length differs by 2.5 % of the height or more.
      const float diff = std::max({std::abs(pa.legs - pb.legs), std::abs(pa.arms - pb.arms), std::abs(pa.trunk - pb.trunk)});
      EXPECT_GT(diff, 0.025f) << morphs[a].name << " / " << morphs[b].name;
    }
  const Proportions child = proportions(morphs[3]);
  const Proportions tall = proportions(morphs[1]);
  EXPECT_LT(child.height, 1.3f);
  EXPECT_GT(tall.height, 1.9f);
  EXPECT_GT(tall.legs, child.legs + 0.03f);  // Long legs vs short limbs.
}

TEST(Morphology, RestPoseStandsOnTheFloorWithTheDefaultJointFrames) {
  const Skeleton base = author::default_skeleton();
  for (const Morphology& m : default_morphologies()) {
    ASSERT_EQ(m.skeleton.num_joints(), base.num_joints());
    const int n = m.skeleton.num_joints();
    std::vector<vec3> pos(static_cast<size_t>(n));
    std::vector<quat> rot(static_cast<size_t>(n));
    const std::vector<quat> identity(static_cast<size_t>(n), quat(1, 0, 0, 0));
    fk_pose(m.skeleton, m.skeleton.rest_offsets_m, identity, pos, rot);
    const vec3 ankle = pos[static_cast<size_t>(m.rig.leg[0].end)];
    const vec3 ball = pos[static_cast<size_t>(m.rig.toe[0])];
    EXPECT_NEAR(ankle.y, m.ankle_height_m, 1e-5f) << m.name;
    EXPECT_NEAR(ball.y, m.ball_height_m, 1e-5f) << m.name;
    for (int j = 1; j < n; ++j) {
      // Scaled bones keep their directions (so the default skeleton's frames stay valid).
      const vec3 a = m.skeleton.rest_offsets_m[static_cast<size_t>(j)], b = base.rest_offsets_m[static_cast<size_t>(j)];
      if (glm::length(b) > 0.0f) {
        EXPECT_GT(glm::dot(glm::normalize(a), glm::normalize(b)), 0.99999f) << m.name << " " << base.joint_names[static_cast<size_t>(j)];
      }
    }
  }
}

TEST(Morphology, IsDeterministicAndUnitScalesGiveTheDefaultSkeleton) {
  const Skeleton base = author::default_skeleton();
  const Skeleton same = scale_default_skeleton(MorphologyScales{});
  for (int j = 0; j < base.num_joints(); ++j)  // The pelvis height is recomputed: rounding only.
    EXPECT_LT(glm::length(same.rest_offsets_m[static_cast<size_t>(j)] - base.rest_offsets_m[static_cast<size_t>(j)]), 1e-6f) << j;
  const std::vector<Morphology> a = default_morphologies(), b = default_morphologies();
  for (size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].skeleton.rest_offsets_m, b[i].skeleton.rest_offsets_m);
  EXPECT_NEAR(default_morphology().height_m, 1.75f, 0.01f);
}

}  // namespace
}  // namespace foresight

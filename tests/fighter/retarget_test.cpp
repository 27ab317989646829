#include "import/bvh_import.hpp"
#include "anim/fk.hpp"
#include "fighter/adaptation_support.hpp"
#include "support/test_paths.hpp"

namespace foresight {
namespace {

using test::FighterCast;

TEST(Retarget, DefaultStrikeClipKeepsPlantedFeetPlantedOnEveryMorphology) {
  FighterCast cast;
  const author::AuthoredClip* c = cast.strike("punch_left_jab_high");
  ASSERT_NE(c, nullptr);
  std::vector<vec3> src, dst;
  fk_clip_positions(cast.library.skeleton, c->clip, src);
  const int ns = cast.library.skeleton.num_joints();
  for (size_t i = 0; i < cast.morphs.size(); ++i) {
    Clip out;
    retarget_clip(cast.source_character(), c->clip, cast.fighter(i), out);
    ASSERT_EQ(out.num_frames, c->clip.num_frames);
    ASSERT_EQ(out.num_joints, cast.morphs[i].skeleton.num_joints());
    fk_clip_positions(cast.morphs[i].skeleton, out, dst);
    const int nd = out.num_joints;
    for (size_t side = 0; side < 2; ++side) {
      const int sj = cast.source_model.contact[side], dj = cast.models[i].contact[side];
      for (int f = 1; f < out.num_frames; ++f) {
        const bool src_planted = glm::length(src[static_cast<size_t>(f * ns + sj)] - src[static_cast<size_t>(sj)]) < 1e-4f;
        if (src_planted) {
          EXPECT_LT(glm::length(dst[static_cast<size_t>(f * nd + dj)] - dst[static_cast<size_t>(dj)]), 1e-3f)
              << cast.morphs[i].name << " frame " << f;
        }
      }
    }
  }
}

TEST(Retarget, PoseLandsWhereTheRootIs) {
  FighterCast cast;
  const author::AuthoredClip* c = cast.strike("kick_left_front_mid");
  ASSERT_NE(c, nullptr);
  PoseBuffers a, b;
  a.resize(cast.morphs[0].skeleton.num_joints());
  b.resize(cast.morphs[0].skeleton.num_joints());
  const Placement there{vec2(3.0f, -1.0f), 2.0f};
  retarget_clip_frame(cast.source_character(), c->clip, 12, cast.fighter(0), Placement{}, a.spans());
  retarget_clip_frame(cast.source_character(), c->clip, 12, cast.fighter(0), there, b.spans());
  for (size_t j = 0; j < a.global_pos_m.size(); ++j)
    EXPECT_LT(glm::length(there.apply(a.global_pos_m[j]) - b.global_pos_m[j]), 1e-4f) << j;
}

TEST(Retarget, MocapTakeOntoMorphologiesKeepsFeetOnTheFloor) {
  FORESIGHT_REQUIRE_MOCAP();
  Skeleton skel;
  Clip clip;
  std::string error;
  ASSERT_TRUE(clip_load_bvh(test::mocap_dir() / "fighting" / "bandai_dataset-1_kick_normal_001.bvh", {}, skel, clip,
                            nullptr, error)) << error;
  LimbModel model;
  ASSERT_TRUE(limb_model_from_clip(skel, clip, 0, model, error)) << error;
  std::vector<vec3> src, dst;
  fk_clip_positions(skel, clip, src);
  const int ns = skel.num_joints();
  FighterCast cast;
  for (size_t i = 0; i < cast.morphs.size(); ++i) {
    Clip out;
    retarget_clip({&skel, &model}, clip, cast.fighter(i), out);
    fk_clip_positions(cast.morphs[i].skeleton, out, dst);
    const int nd = out.num_joints;
    const float scale = cast.models[i].leg_length_m / model.leg_length_m;
    for (int f = 0; f < clip.num_frames; ++f) {
      for (size_t side = 0; side < 2; ++side) {
        // The foot's clearance above the floor scales with the legs: on the floor stays on it.
        const float src_clear = src[static_cast<size_t>(f * ns + model.contact[side])].y - model.contact_height_m[side];
        const float dst_clear = dst[static_cast<size_t>(f * nd + cast.models[i].contact[side])].y - cast.morphs[i].ball_height_m;
        EXPECT_NEAR(dst_clear, src_clear * scale, 0.002f) << cast.morphs[i].name << " frame " << f;
      }
    }
  }
}

}  // namespace
}  // namespace foresight

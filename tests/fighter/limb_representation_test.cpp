#include "author/default_library.hpp"
#include "import/bvh_import.hpp"
#include "anim/fk.hpp"
#include "fighter/limb_representation.hpp"
#include "fighter/morphology.hpp"
#include "fighter/retarget.hpp"
#include "support/test_paths.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace foresight {
namespace {

// Encodes every frame of `clip` on `s` and decodes it back onto `s`; the worst joint error.
float worst_round_trip_m(const Skeleton& s, const LimbModel& model, const Clip& clip, const Placement& root) {
  const int n = s.num_joints();
  PoseBuffers out;
  out.resize(n);
  std::vector<vec3> ref(static_cast<size_t>(n));
  std::vector<quat> ref_rot(static_cast<size_t>(n));
  float worst = 0.0f;
  for (int f = 0; f < clip.num_frames; ++f) {
    LimbPose limb;
    limb_pose_encode(s, model, clip.frame_pos(f), clip.frame_rot(f), root, limb);
    limb_pose_decode(s, model, limb, root, out.spans());
    fk_pose(s, clip.frame_pos(f), clip.frame_rot(f), ref, ref_rot);
    for (int j = 0; j < n; ++j) {
      const float e = glm::length(out.global_pos_m[static_cast<size_t>(j)] - ref[static_cast<size_t>(j)]);
      EXPECT_TRUE(std::isfinite(e));
      worst = std::max(worst, e);
    }
  }
  return worst;
}

TEST(LimbRepresentation, RoundTripReproducesEveryDefaultStrikeFrame) {
  const author::DefaultLibrarySpec lib = author::build_default_library();
  const Morphology def = default_morphology();
  LimbModel model;
  std::string error;
  ASSERT_TRUE(limb_model_for_morphology(def, model, error)) << error;
  int strikes = 0;
  for (const author::AuthoredClip& c : lib.clips) {
    if (!c.strike) continue;
    ++strikes;
    // Also away from the origin and turned: the representation is root-relative.
    EXPECT_LT(worst_round_trip_m(lib.skeleton, model, c.clip, Placement{}), 0.001f) << c.clip.name;
  }
  EXPECT_GE(strikes, 16);
}

TEST(LimbRepresentation, RoundTripReproducesAMocapTake) {
  FORESIGHT_REQUIRE_MOCAP();
  Skeleton s;
  Clip clip;
  std::string error;
  ASSERT_TRUE(clip_load_bvh(test::mocap_dir() / "fighting" / "bandai_dataset-1_kick_normal_001.bvh", {}, s, clip,
                            nullptr, error)) << error;
  LimbModel model;
  ASSERT_TRUE(limb_model_from_clip(s, clip, 0, model, error)) << error;
  EXPECT_LT(worst_round_trip_m(s, model, clip, Placement{vec2(0.3f, -0.2f), 0.4f}), 0.001f);
}

TEST(LimbRepresentation, DecodingOntoMorphologiesKeepsFeetOnTheGroundAndArmDirections) {
  const author::DefaultLibrarySpec lib = author::build_default_library();
  const Morphology def = default_morphology();
  LimbModel src_model;
  std::string error;
  ASSERT_TRUE(limb_model_for_morphology(def, src_model, error)) << error;
  std::vector<vec3> src_pos;
  for (const Morphology& morph : default_morphologies()) {
    LimbModel model;
    ASSERT_TRUE(limb_model_for_morphology(morph, model, error)) << error;
    PoseBuffers out;
    out.resize(morph.skeleton.num_joints());
    for (const author::AuthoredClip& c : lib.clips) {
      if (!c.strike) continue;
      fk_clip_positions(lib.skeleton, c.clip, src_pos);
      const int n = lib.skeleton.num_joints();
      for (int f = 0; f < c.clip.num_frames; ++f) {
        LimbPose limb;
        limb_pose_encode(lib.skeleton, src_model, c.clip.frame_pos(f), c.clip.frame_rot(f), Placement{}, limb);
        limb_pose_decode(morph.skeleton, model, limb, Placement{}, out.spans());
        for (int side = 0; side < 2; ++side) {
          // A ball of the foot on the floor in the source is on the floor on every morphology.
          const int toe = src_model.contact[static_cast<size_t>(side)];
          const float src_clear = src_pos[static_cast<size_t>(f * n + toe)].y - def.ball_height_m;
          const float dst_clear = out.global_pos_m[static_cast<size_t>(model.contact[static_cast<size_t>(side)])].y -
                                  morph.ball_height_m;
          if (std::abs(src_clear) < 1e-4f) {
            EXPECT_NEAR(dst_clear, 0.0f, 1e-3f) << morph.name << " " << c.clip.name;
          }
          // The arm points the same way (the wrist lies along the same shoulder -> wrist line).
          const FighterLimb& sa = src_model.rig.arm[static_cast<size_t>(side)];
          const FighterLimb& da = model.rig.arm[static_cast<size_t>(side)];
          const vec3 sd = glm::normalize(src_pos[static_cast<size_t>(f * n + sa.end)] - src_pos[static_cast<size_t>(f * n + sa.root)]);
          const vec3 dd = glm::normalize(out.global_pos_m[static_cast<size_t>(da.end)] - out.global_pos_m[static_cast<size_t>(da.root)]);
          EXPECT_GT(glm::dot(sd, dd), std::cos(radians(1.0f))) << morph.name << " " << c.clip.name << " frame " << f;
        }
      }
    }
  }
}

}  // namespace
}  // namespace foresight

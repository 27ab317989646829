#include "fighter/adaptation_support.hpp"

namespace foresight {
namespace {

using test::FighterCast;

// The support foot's contact joint (ball of the foot) over a whole adapted strike: how far it gets
// from where it was at the first frame.
float support_drift_m(const FighterCast& cast, size_t i, const StrikeRequest& req, int* ccd_frames) {
  StrikeAdapter adapter;
  std::string error;
  EXPECT_TRUE(adapter.begin(req, cast.fighter(i), AdaptSettings{}, {}, {}, error)) << error;
  const size_t support = static_cast<size_t>(adapter.support_contact_joint());
  vec3 first(0.0f);
  float drift = 0.0f;
  for (int k = 0; k < adapter.num_frames(); ++k) {
    const AdaptedFrame f = adapter.pose_frame(k);
    if (f.ccd_iterations > 0) ++*ccd_frames;
    const vec3 p = adapter.pose().global_pos_m[support];
    if (k == 0) first = p;
    drift = std::max(drift, glm::length(p - first));
  }
  return drift;
}

TEST(AdaptStrike, KickKeepsTheSupportFootPlanted) {
  FighterCast cast;
  const Placement alignment{vec2(-0.4f, 0.9f), -1.2f};
  int ccd_frames = 0;
  for (const char* name : {"kick_left_front_high", "kick_right_roundhouse_mid", "kick_right_front_low"}) {
    const author::AuthoredClip* c = cast.strike(name);
    ASSERT_NE(c, nullptr) << name;
    // High and far: most morphologies need the pelvis tilt (which turns about the support hip).
    const vec3 target = alignment.apply(vec3(0.0f, 1.25f, 0.75f));
    for (size_t i = 0; i < cast.morphs.size(); ++i)
      EXPECT_LT(support_drift_m(cast, i, cast.request(*c, alignment, target), &ccd_frames), 0.01f)
          << name << " on " << cast.morphs[i].name;
  }
  EXPECT_GT(ccd_frames, 0);  // The torso solver ran, so the re-planted support leg was exercised.
}

TEST(AdaptStrike, PunchKeepsBothFeetPlanted) {
  FighterCast cast;
  const author::AuthoredClip* c = cast.strike("punch_right_cross_high");
  ASSERT_NE(c, nullptr);
  for (size_t i = 0; i < cast.morphs.size(); ++i) {
    StrikeAdapter adapter;
    std::string error;
    ASSERT_TRUE(adapter.begin(cast.request(*c, Placement{}, vec3(-0.1f, 1.2f, 0.8f)), cast.fighter(i), AdaptSettings{}, {},
                              {}, error)) << error;
    std::array<vec3, 2> first{};
    for (int k = 0; k < adapter.num_frames(); ++k) {
      adapter.pose_frame(k);
      for (size_t side = 0; side < 2; ++side) {
        const vec3 p = adapter.pose().global_pos_m[static_cast<size_t>(cast.models[i].contact[side])];
        if (k == 0) first[side] = p;
        EXPECT_LT(glm::length(p - first[side]), 0.01f) << cast.morphs[i].name << " frame " << k;
      }
    }
  }
}

TEST(AdaptStrike, BlendsFromTheCurrentPose) {
  FighterCast cast;
  const author::AuthoredClip* c = cast.strike("punch_left_jab_mid");
  ASSERT_NE(c, nullptr);
  // The current pose: the last frame of another strike, retargeted onto the fighter.
  const author::AuthoredClip* other = cast.strike("kick_right_front_low");
  ASSERT_NE(other, nullptr);
  PoseBuffers current;
  current.resize(cast.morphs[1].skeleton.num_joints());
  retarget_clip_frame(cast.source_character(), other->clip, 10, cast.fighter(1), Placement{}, current.spans());
  StrikeAdapter adapter;
  std::string error;
  AdaptSettings settings;
  settings.blend_frames = 6;
  ASSERT_TRUE(adapter.begin(cast.request(*c, Placement{}, vec3(0.05f, 1.3f, 0.6f)), cast.fighter(1), settings,
                            current.local_pos_m, current.local_rot, error)) << error;
  adapter.pose_frame(0);
  // Frame 0 is the current pose (the kicking foot still in the air), not the strike's stance.
  float worst = 0.0f;
  for (size_t j = 0; j < current.global_pos_m.size(); ++j)
    worst = std::max(worst, glm::length(adapter.retargeted().global_pos_m[j] - current.global_pos_m[j]));
  EXPECT_LT(worst, 0.002f);
  // By the end of the blend it is the strike alone.
  PoseBuffers plain;
  plain.resize(cast.morphs[1].skeleton.num_joints());
  adapter.pose_frame(settings.blend_frames);
  retarget_clip_frame(cast.source_character(), c->clip, settings.blend_frames, cast.fighter(1), Placement{}, plain.spans());
  worst = 0.0f;
  for (size_t j = 0; j < plain.global_pos_m.size(); ++j)
    worst = std::max(worst, glm::length(adapter.retargeted().global_pos_m[j] - plain.global_pos_m[j]));
  EXPECT_LT(worst, 1e-4f);
}

}  // namespace
}  // namespace foresight

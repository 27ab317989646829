#include "support/test_paths.hpp"
#include "fighter/adaptation_support.hpp"

#include <cmath>

namespace foresight {
namespace {

using test::FighterCast;

// Plays the whole strike on morphology i; returns the hit frame's report and checks every frame.
AdaptedFrame play(const FighterCast& cast, size_t i, const StrikeRequest& req, float* unadapted_miss_m = nullptr) {
  StrikeAdapter adapter;
  std::string error;
  EXPECT_TRUE(adapter.begin(req, cast.fighter(i), AdaptSettings{}, {}, {}, error)) << error;
  if (unadapted_miss_m) *unadapted_miss_m = glm::length(adapter.unadapted_hit_m() - req.target_m);
  AdaptedFrame hit;
  for (int k = 0; k < adapter.num_frames(); ++k) {
    const AdaptedFrame f = adapter.pose_frame(k);
    for (const vec3& p : adapter.pose().global_pos_m) EXPECT_TRUE(test::finite(p)) << cast.morphs[i].name;
    if (k == adapter.hit_index()) hit = f;
  }
  return hit;
}

void expect_same_target_reached(const char* clip_name, vec3 local_target) {
  FighterCast cast;
  const author::AuthoredClip* c = cast.strike(clip_name);
  ASSERT_NE(c, nullptr) << clip_name;
  const Placement alignment{vec2(1.5f, -2.0f), 0.7f};
  const vec3 target = alignment.apply(local_target);
  float largest_miss = 0.0f;
  for (size_t i = 0; i < cast.morphs.size(); ++i) {
    float miss = 0.0f;
    const AdaptedFrame hit = play(cast, i, cast.request(*c, alignment, target), &miss);
    largest_miss = std::max(largest_miss, miss);
    EXPECT_LT(glm::length(hit.effector_m - target), 0.01f) << cast.morphs[i].name << " " << clip_name;
    EXPECT_LT(hit.reach_error_m, 0.01f) << cast.morphs[i].name;
  }
  // The retargeted strikes alone miss by far: the adaptation did the work.
  EXPECT_GT(largest_miss, 0.10f);
}

TEST(AdaptStrike, SamePunchReachesTheSameTargetOnFiveMorphologies) {
  // Far enough ahead that the child morphology must lean its torso in (CCD), the others not.
  expect_same_target_reached("punch_left_jab_mid", vec3(0.05f, 1.0f, 0.55f));
}

TEST(AdaptStrike, SameKickReachesTheSameTargetOnFiveMorphologies) {
  // The child morphology must tilt its pelvis (CCD) to get there.
  expect_same_target_reached("kick_right_front_mid", vec3(-0.05f, 0.8f, 0.6f));
}

TEST(AdaptStrike, UnreachableTargetIsApproachedAsCloselyAsPossible) {
  FighterCast cast;
  for (const char* name : {"punch_right_cross_high", "kick_left_front_high"}) {
    const author::AuthoredClip* c = cast.strike(name);
    ASSERT_NE(c, nullptr) << name;
    const vec3 target(0.3f, 2.6f, 3.0f);  // Far up and ahead: nobody reaches it.
    for (size_t i = 0; i < cast.morphs.size(); ++i) {
      const StrikeRequest req = cast.request(*c, Placement{}, target);
      StrikeAdapter adapter;
      std::string error;
      ASSERT_TRUE(adapter.begin(req, cast.fighter(i), AdaptSettings{}, {}, {}, error)) << error;
      const AdaptedFrame hit = [&] {
        AdaptedFrame h;
        for (int k = 0; k < adapter.num_frames(); ++k) {
          const AdaptedFrame f = adapter.pose_frame(k);
          EXPECT_TRUE(test::finite(f.effector_m) && std::isfinite(f.reach_error_m)) << name;
          for (const vec3& p : adapter.pose().global_pos_m) EXPECT_TRUE(test::finite(p));
          if (k == adapter.hit_index()) h = f;
        }
        return h;
      }();
      adapter.pose_frame(adapter.hit_index());
      EXPECT_FALSE(hit.reachable);
      // As close as possible: the limb is straight and points at the target, and the torso helped
      // (the effector is nearer than the unadapted strike's).
      const FighterRig& rig = cast.models[i].rig;
      const FighterLimb& limb = req.kick ? rig.leg[static_cast<size_t>(req.side)] : rig.arm[static_cast<size_t>(req.side)];
      const vec3 root = adapter.pose().global_pos_m[static_cast<size_t>(limb.root)];
      EXPECT_NEAR(glm::length(hit.effector_m - root), limb.length_m(), 0.002f) << name << " " << cast.morphs[i].name;
      EXPECT_GT(glm::dot(glm::normalize(hit.effector_m - root), glm::normalize(target - root)), std::cos(radians(1.0f)));
      EXPECT_LT(glm::length(hit.effector_m - target), glm::length(adapter.unadapted_hit_m() - target) - 0.02f);
      EXPECT_GT(hit.ccd_iterations, 0);
    }
  }
}

TEST(AdaptStrike, BadRequestsAreRefused) {
  FighterCast cast;
  const author::AuthoredClip* c = cast.strike("punch_left_jab_mid");
  ASSERT_NE(c, nullptr);
  StrikeRequest req = cast.request(*c, Placement{}, vec3(0, 1, 0.5f));
  StrikeAdapter adapter;
  std::string error;
  req.hit_frame = c->clip.num_frames + 3;
  EXPECT_FALSE(adapter.begin(req, cast.fighter(0), AdaptSettings{}, {}, {}, error));
  EXPECT_NE(error.find("frames"), std::string::npos) << error;
  req = cast.request(*c, Placement{}, vec3(0, 1, 0.5f));
  req.clip = nullptr;
  EXPECT_FALSE(adapter.begin(req, cast.fighter(0), AdaptSettings{}, {}, {}, error));
}

}  // namespace
}  // namespace foresight

// The procedural toolkit on its own: two-bone IK, key tracks, easing, foot timelines.
#include "author/easing.hpp"
#include "author/footsteps.hpp"
#include "author/key_track.hpp"
#include "author/two_bone_ik.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace foresight::author {
namespace {

// Forward kinematics of the solved chain: the end joint from the returned rotations.
vec3 chain_end(vec3 root, const TwoBoneSolution& s, float upper, float lower) {
  const vec3 mid = root + s.upper_global * vec3(0, -upper, 0);
  return mid + (s.upper_global * s.lower_local) * vec3(0, -lower, 0);
}

TEST(TwoBoneIk, ReachesTargetsInsideTheReach) {
  const vec3 hip(0.1f, 0.9f, 0.0f);
  for (float x = -0.3f; x <= 0.3f; x += 0.15f)
    for (float y = 0.1f; y <= 0.8f; y += 0.175f)
      for (float z = -0.3f; z <= 0.45f; z += 0.15f) {
        const vec3 target(x, y, z);
        if (glm::length(target - hip) > 0.99f * 0.84f || glm::length(target - hip) < 0.05f) continue;
        const TwoBoneSolution s =
            solve_two_bone(hip, target, 0.42f, 0.42f, vec3(0, 0, 1), HingeSide::kKnee);
        EXPECT_TRUE(s.reached);
        EXPECT_LT(glm::length(chain_end(hip, s, 0.42f, 0.42f) - target), 1e-4f);
        EXPECT_NEAR(glm::length(s.mid_m - hip), 0.42f, 1e-4f);
      }
}

TEST(TwoBoneIk, KneeBendsForwardAndElbowBendsBack) {
  const vec3 hip(0, 0.9f, 0);
  const TwoBoneSolution knee =
      solve_two_bone(hip, vec3(0, 0.2f, 0), 0.42f, 0.42f, vec3(0, 0, 1), HingeSide::kKnee);
  EXPECT_GT(knee.mid_m.z, 0.1f);
  // A knee folds about its X axis with the shin swinging back (towards the thigh's -Z).
  EXPECT_GT(glm::angle(knee.lower_local), 0.5f);
  EXPECT_LT((knee.lower_local * vec3(0, -1, 0)).z, -0.3f);
  const vec3 shoulder(0.18f, 1.43f, 0);
  const TwoBoneSolution elbow = solve_two_bone(shoulder, vec3(0.1f, 1.4f, 0.3f), 0.28f, 0.26f,
                                               vec3(0, -1, -0.3f), HingeSide::kElbow);
  EXPECT_LT(elbow.mid_m.y, 1.3f);
  EXPECT_LT(glm::length(chain_end(shoulder, elbow, 0.28f, 0.26f) - vec3(0.1f, 1.4f, 0.3f)), 1e-4f);
  // The upper arm keeps its natural twist: its local +Z (front) faces the hand side.
  EXPECT_GT(glm::dot(elbow.upper_global * vec3(0, 0, 1), vec3(0.1f, 1.4f, 0.3f) - elbow.mid_m), 0.0f);
}

TEST(TwoBoneIk, OutOfReachTargetsAreApproachedWithoutSnapping) {
  const vec3 hip(0, 0.9f, 0);
  float previous = 0.79f;
  for (float d = 0.80f; d <= 1.2f; d += 0.01f) {
    const TwoBoneSolution s =
        solve_two_bone(hip, hip + vec3(0, -d, 0), 0.42f, 0.42f, vec3(0, 0, 1), HingeSide::kKnee);
    const float reach = glm::length(s.end_m - hip);
    EXPECT_LT(reach, 0.84f);
    EXPECT_GE(reach, previous - 1e-6f);  // monotone: no pop as the target moves away
    EXPECT_LT(reach - previous, 0.0101f);
    previous = reach;
  }
}

TEST(KeyTrack, PassesThroughKeysAndStopsAtHolds) {
  KeyTrack<float> k;
  k.key(0.0f, 0.0f, true).key(0.5f, 1.0f).key(1.0f, 3.0f, true).key(2.0f, 0.0f, true);
  EXPECT_FLOAT_EQ(k.at(0.0f), 0.0f);
  EXPECT_FLOAT_EQ(k.at(0.5f), 1.0f);
  EXPECT_FLOAT_EQ(k.at(1.0f), 3.0f);
  EXPECT_FLOAT_EQ(k.at(3.0f), 0.0f);
  const float eps = 1e-3f;
  EXPECT_NEAR((k.at(1.0f + eps) - k.at(1.0f - eps)) / (2 * eps), 0.0f, 0.05f);
  // The non-held key is passed through with a Catmull-Rom velocity (3 / 1 s), not stopped at.
  EXPECT_NEAR((k.at(0.5f + eps) - k.at(0.5f - eps)) / (2 * eps), 3.0f, 0.05f);
}

TEST(Easing, EndsAndSoftMin) {
  EXPECT_FLOAT_EQ(smoothstep01(0.0f), 0.0f);
  EXPECT_FLOAT_EQ(smoothstep01(1.0f), 1.0f);
  EXPECT_FLOAT_EQ(smootherstep01(0.5f), 0.5f);
  for (float a = 0.0f; a < 1.0f; a += 0.05f) {
    EXPECT_LE(soft_min(a, 0.5f, 0.1f), std::min(a, 0.5f) + 1e-7f);
    EXPECT_GE(soft_min(a, 0.5f, 0.1f), std::min(a, 0.5f) - 0.025f - 1e-7f);
  }
  EXPECT_NEAR(wrap_angle(lerp_angle(radians(170), radians(-170), 0.5f)), kPi, 1e-5f);
  const quat q = quat_ypr(0.3f, 0.0f, 0.0f);
  EXPECT_NEAR(heading_of(q * vec3(0, 0, 1)), 0.3f, 1e-6f);
}

TEST(FootTimeline, PlantedFootIsPinnedAndRollsAboutTheBall) {
  const FootGeometry g;
  FootPlant a;
  a.ankle_xz_m = vec2(0.1f, 0.2f);
  a.land_s = -1.0f;
  a.heel_off_s = 0.3f;
  a.lift_s = 0.5f;
  a.lift_pitch_rad = 0.6f;
  FootPlant b = a;
  b.ankle_xz_m = vec2(0.1f, 1.4f);
  b.yaw_rad = 0.3f;
  b.land_s = 0.9f;
  b.heel_off_s = b.lift_s = kOpenFutureS;
  const FootTimeline keys = {plant_key(a), plant_key(b)};
  const auto shape = [](float) { return SwingShape{}; };
  const auto root = [](float) { return Placement{}; };
  const vec3 ball0 = from_ground(a.ankle_xz_m, g.ankle_height_m) + g.ball_from_ankle_m;
  for (float t = 0.0f; t <= 1.2f; t += 0.01f) {
    const FootSample s = sample_foot(keys, t, g, 1.0f, 0.2f, shape, root);
    EXPECT_GE(sole_clearance(g, s.ankle_m, s.yaw_rad, s.pitch_rad, s.toe_bend_rad), -1e-5f) << t;
    if (t <= 0.3f) { EXPECT_LT(glm::length(s.ankle_m - from_ground(a.ankle_xz_m, g.ankle_height_m)), 1e-6f); }
    if (t > 0.3f && t <= 0.5f) {
      // Heel rolling: the ball stays put while the ankle rises.
      const vec3 ball = s.ankle_m + quat_ypr(s.yaw_rad, s.pitch_rad, 0) * g.ball_from_ankle_m;
      EXPECT_LT(glm::length(ball - ball0), 1e-5f) << t;
      EXPECT_GT(s.ankle_m.y, g.ankle_height_m);
    }
    if (t >= 0.9f) {
      EXPECT_TRUE(s.planted);
      EXPECT_LT(glm::length(ground(s.ankle_m) - b.ankle_xz_m), 1e-5f);
    }
    if (t > 0.55f && t < 0.85f) { EXPECT_FALSE(s.planted); }
  }
  // The swing lifts the foot well clear at its top.
  EXPECT_GT(sample_foot(keys, 0.65f, g, 1.0f, 0.2f, shape, root).ankle_m.y, g.ankle_height_m + 0.04f);
}

TEST(FootTimeline, APivotTurnsTheFootAboutItsPinnedBall) {
  // A turning step's stance foot: flat, then heel up and pivoting 45 deg on the ball of the foot,
  // the ball never moving.
  const FootGeometry g;
  FootPlant p;
  p.ankle_xz_m = vec2(-0.05f, 0.35f);
  p.yaw_rad = -0.12f;
  p.land_s = 0.0f;
  p.heel_off_s = 0.3f;
  p.lift_s = 0.6f;
  p.lift_pitch_rad = 0.6f;
  p.pivot_rad = radians(45.0f);
  p.pivot_end_s = 0.5f;
  const FootTimeline keys = {plant_key(p)};
  const auto shape = [](float) { return SwingShape{}; };
  const auto root = [](float) { return Placement{}; };
  const vec2 ball = p.ball_xz(g);
  for (float t = 0.0f; t <= 0.55f; t += 0.01f) {
    const FootSample s = sample_foot(keys, t, g, -1.0f, 0.2f, shape, root);
    const vec3 b = s.ankle_m + quat_ypr(s.yaw_rad, s.pitch_rad, 0) * g.ball_from_ankle_m;
    EXPECT_LT(glm::length(ground(b) - ball), 1e-5f) << t;
    EXPECT_NEAR(b.y, g.ankle_height_m + g.ball_from_ankle_m.y, 1e-5f) << t;
    if (t <= 0.3f) { EXPECT_FLOAT_EQ(s.yaw_rad, p.yaw_rad); }
    if (t >= 0.5f) { EXPECT_NEAR(s.yaw_rad, p.yaw_rad + p.pivot_rad, 1e-6f); }
  }
  // The pivot eases in and out: no yaw speed as it starts or ends.
  EXPECT_NEAR(p.yaw_at(0.301f), p.yaw_rad, 1e-4f);
  EXPECT_NEAR(p.yaw_at(0.499f), p.yaw_rad + p.pivot_rad, 1e-4f);
}

}  // namespace
}  // namespace foresight::author

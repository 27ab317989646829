#include "author/gait.hpp"

#include "author/easing.hpp"

#include <algorithm>
#include <cmath>

namespace foresight::author {
namespace {

// Smoothness of the leg-reach limit on the pelvis height (metres of blending).
constexpr float kReachSoftness = 0.03f;
// Hip-ankle distance over which a loaded leg compresses in a run (dip shape).
constexpr float kDipRadiusM = 0.4f;
constexpr float kMaxTwistRad = 0.4f;
constexpr float kMaxArmSwingRad = 0.7f;

float style_weight(const LocomotionSpec& spec, float t) {
  if (spec.style_blend_end_s <= spec.style_blend_begin_s) return t < spec.style_blend_begin_s ? 0.0f : 1.0f;
  return smootherstep01((t - spec.style_blend_begin_s) /
                        (spec.style_blend_end_s - spec.style_blend_begin_s));
}

// Time step of the finite difference behind the pelvis yaw (ball-of-foot speeds).
constexpr float kSpeedStepS = 1.0e-3f;

}  // namespace

int LocomotionSpec::num_frames(float fps) const {
  return static_cast<int>(std::lround(duration_s * fps)) + 1;
}

FootGeometry foot_geometry(const Rig& rig) {
  FootGeometry g;
  g.ankle_height_m = rig.ankle_height_m;
  g.ball_from_ankle_m = rig.ball_from_ankle_m;
  g.toe_from_ball_m = rig.toe_from_ball_m;
  g.sole_below_ball_m = rig.ankle_height_m + rig.ball_from_ankle_m.y;
  g.heel_from_ankle_m = vec3(0.0f, -rig.ankle_height_m, -0.05f);
  return g;
}

GaitStyle style_at(const LocomotionSpec& spec, float t) {
  return mix(gait_family(spec.start_family).style, gait_family(spec.end_family).style,
             style_weight(spec, t));
}

namespace {

// Pelvis height: nominal, minus a running leg's compression, then softly limited so both legs
// reach their ankles. The limit is what makes a walking pelvis dip at double support.
float pelvis_height(const Skeleton& skeleton, const Rig& rig, const GaitStyle& style,
                    const std::array<FootSample, 2>& feet, vec2 pelvis_xz, const quat& pelvis_rot,
                    float nominal_m) {
  const float reach = style.reach_fraction * (rig.leg[kLeft].upper_m + rig.leg[kLeft].lower_m);
  std::array<vec3, 2> hip_rel;
  std::array<float, 2> hip_to_ankle;
  float dip = 0.0f;
  for (int side = 0; side < 2; ++side) {
    hip_rel[side] = pelvis_rot * skeleton.rest_offsets_m[rig.leg[side].root];
    hip_to_ankle[side] = glm::length(pelvis_xz + ground(hip_rel[side]) - ground(feet[side].ankle_m));
    const float x = std::max(0.0f, 1.0f - glm::pow(hip_to_ankle[side] / kDipRadiusM, 2.0f));
    dip += feet[side].load * x * x;
  }
  float height = nominal_m - style.stance_dip_m * std::min(dip, 1.0f);
  for (int side = 0; side < 2; ++side) {
    const float d = hip_to_ankle[side];
    if (d >= reach) continue;  // Out of reach whatever the height: the IK softens it.
    const float highest = feet[side].ankle_m.y - hip_rel[side].y + std::sqrt(reach * reach - d * d);
    height = soft_min(height, highest, kReachSoftness);
  }
  return height;
}

// A hanging arm swung forward by `swing_rad` (negative: back), as the wrist and elbow direction
// the body pose wants (shoulder-relative, chest axes); blended towards the guard by style.guard.
ArmPose arm_pose(const Rig& rig, const GaitStyle& style, int side, float swing_rad) {
  const float s = side_sign(side);
  const float flex = style.arm_flex_rad + swing_rad;
  const float elbow = style.elbow_rad + style.elbow_swing_rad_per_rad * std::max(0.0f, swing_rad);
  const quat upper = glm::angleAxis(s * style.arm_abduction_rad, vec3(0, 0, 1)) *
                     glm::angleAxis(-flex, vec3(1, 0, 0));
  const quat fore = upper * glm::angleAxis(-elbow, vec3(1, 0, 0));
  const LimbRig& arm = rig.arm[side];
  const vec3 hang_wrist = upper * vec3(0, -arm.upper_m, 0) + fore * vec3(0, -arm.lower_m, 0);
  const vec3 hang_elbow = upper * glm::normalize(vec3(s * 0.3f, 0.0f, -1.0f));
  // Raising the guard bows the hands forward, clear of the trunk.
  const float gw = clamp01(style.guard);
  ArmPose a;
  a.wrist_m = lerp(hang_wrist, guard_wrist_m(side), gw) + vec3(0, 0, 0.12f * std::sin(kPi * gw));
  a.elbow_dir = lerp(hang_elbow, guard_elbow_dir(side), gw);
  return a;
}

}  // namespace

BodyPose gait_pose(const Skeleton& skeleton, const Rig& rig, const LocomotionSpec& spec, float t) {
  const GaitStyle style = style_at(spec, t);
  const Placement root = spec.path.at(t);
  const Placement to_root = root.inverse();
  const FootGeometry g = foot_geometry(rig);
  const auto shape_at = [&spec](float time) { return style_at(spec, time).swing; };
  const auto root_at = [&spec](float time) { return spec.path.at(time); };
  const float phase = kTwoPi * t / spec.duration_s;
  const StandingMotion& sm = spec.standing;

  const auto sample = [&](int side, float time) {
    return sample_foot(spec.feet[side], time, g, side_sign(side), style.weight_accept_s, shape_at,
                       root_at);
  };
  const auto ball = [&g](const FootSample& f) {
    return ground(f.ankle_m + quat_ypr(f.yaw_rad, f.pitch_rad, 0.0f) * g.ball_from_ankle_m);
  };
  // Speeds by a difference kept inside the clip (the timelines cover [0, duration] only).
  const float t0 = std::max(0.0f, t - kSpeedStepS), t1 = std::min(spec.duration_s, t + kSpeedStepS);
  const vec2 forward = rotate_ground(vec2(0.0f, 1.0f), root.heading_rad);

  std::array<FootSample, 2> feet;
  std::array<vec2, 2> local;  // ankles in the root frame: x = side, y = forward
  std::array<float, 2> ball_speed{0.0f, 0.0f};  // forward speed of the ball of each foot
  float support_x = 0.0f;
  for (int side = 0; side < 2; ++side) {
    feet[side] = sample(side, t);
    local[side] = to_root.apply(ground(feet[side].ankle_m));
    support_x += feet[side].load * local[side].x;
    if (t1 > t0)
      ball_speed[side] =
          glm::dot(ball(sample(side, t1)) - ball(sample(side, t0)), forward) / (t1 - t0);
  }
  const float fore_aft = local[kLeft].y - local[kRight].y;

  BodyPose pose;
  // Pelvis: sways over the loaded foot (loads are bells over each stance, so the sway is a smooth
  // side-to-side wave that crosses the middle at double support), yaws so the swinging leg's hip
  // comes forward with it, lists up on the loaded side. The yaw follows the balls of the feet's
  // speeds, not how far apart the feet are: it is zero whenever both balls are still - at every
  // walking foot strike - so the root heading (taken from the pelvis) is the path's heading at
  // those boundaries and a straight step measures as straight.
  const float sway = style.sway_gain * support_x + sm.sway_m * std::sin(phase);
  const auto drive = [](float v) { return v * std::abs(v) / (kTwistSpeedMps * kTwistSpeedMps); };
  const float drive_lr = drive(ball_speed[kLeft]) - drive(ball_speed[kRight]);
  const float twist = std::clamp(-style.twist_rad * drive_lr, -kMaxTwistRad, kMaxTwistRad);
  const float roll = style.list_rad * (feet[kLeft].load - feet[kRight].load);
  const float heading = root.heading_rad + twist;
  // The list is about the horizontal forward axis, not the pitched pelvis's own: it then leaves the
  // hip axis's ground projection (which the root heading is taken from) alone, also in a crouch.
  pose.pelvis_rot = glm::angleAxis(heading, vec3(0, 1, 0)) * glm::angleAxis(roll, vec3(0, 0, 1)) *
                    glm::angleAxis(style.pelvis_pitch_rad, vec3(1, 0, 0));
  const vec2 pelvis_xz = root.apply(vec2(sway, -style.pelvis_back_m));
  const float nominal = style.pelvis_height_m +
                        sm.bounce_m * std::sin(phase * static_cast<float>(sm.bounce_cycles));
  pose.pelvis_m = from_ground(
      pelvis_xz, pelvis_height(skeleton, rig, style, feet, pelvis_xz, pose.pelvis_rot, nominal));

  // Trunk: the chest turns against the legs (right shoulder forward as the left foot leads, with
  // the arms) whatever the pelvis does, and rolls back towards level; the head looks along the
  // path.
  const float chest_yaw = style.chest_counter_rad_per_m * fore_aft;
  pose.spine_ypr_rad = vec3(style.spine_yaw_rad + chest_yaw - twist,
                            style.spine_pitch_rad - sm.breathe_rad * std::sin(phase), -0.8f * roll);
  pose.head_rot = quat_ypr(root.heading_rad, style.head_pitch_rad, 0.0f);

  for (int side = 0; side < 2; ++side) {
    // Arms swing opposite the legs: forward as the other foot leads.
    const float swing = std::clamp(style.arm_swing_rad_per_m * (local[1 - side].y - local[side].y),
                                   -kMaxArmSwingRad, kMaxArmSwingRad);
    pose.arms[side] = arm_pose(rig, style, side, swing);
    pose.clavicle_rad[side] =
        vec2(style.clavicle_raise_rad + 0.5f * sm.breathe_rad * std::sin(phase), 0.0f);

    FootPose& foot = pose.feet[side];
    foot.ankle_m = feet[side].ankle_m;
    foot.rot = quat_ypr(feet[side].yaw_rad, feet[side].pitch_rad, 0.0f);
    foot.toe_bend_rad = feet[side].toe_bend_rad;
    // Knees track a loaded foot (knee over toes) but, while the foot swings, mostly where the
    // body faces, and always a little outwards (the knees of a turning walk stay apart).
    const float l = feet[side].load;
    foot.knee_dir = glm::normalize(forward3(feet[side].yaw_rad) * (0.3f + 0.4f * l) +
                                   forward3(heading) * (0.7f - 0.4f * l) +
                                   left3(heading) * (0.12f * side_sign(side)));
  }
  return pose;
}

Clip bake_locomotion(const Skeleton& skeleton, const Rig& rig, const LocomotionSpec& spec) {
  return bake_clip(skeleton, rig, spec.name, spec.num_frames(kFps), kFps,
                   [&](float t) { return gait_pose(skeleton, rig, spec, t); });
}

}  // namespace foresight::author

#include "anim/author/gait.hpp"

#include "anim/author/easing.hpp"

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

GaitStyle style_at(const LocomotionSpec& spec, float t) {
  return mix(gait_family(spec.start_family).style, gait_family(spec.end_family).style,
             style_weight(spec, t));
}

FootPlant neutral_plant(const GaitFamily& f, int side, const Placement& root, float land_s,
                        float cycle_offset) {
  // A plant of the family's straight, steady cycle. cycle_offset: how many cycles after the
  // boundary's left plant this one comes (0: that plant; -0.5: the right plant before it; 0.5:
  // the right plant after it).
  const float s = f.stance_fraction, c = f.cycle_s, d = f.stride_m;
  FootPlant p;
  const float sign = side_sign(side);
  p.ankle_xz_m = root.apply(vec2(sign * f.step_width_m, d * (s * 0.5f + cycle_offset) + f.foot_forward_m));
  p.yaw_rad = root.heading_rad + sign * f.toe_out_rad;
  p.land_s = land_s;
  p.lift_s = land_s + s * c;
  p.heel_off_s = p.lift_s - f.heel_off_fraction * c;
  p.lift_pitch_rad = f.style.lift_pitch_rad;
  return p;
}

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

FootKey boundary_key(const GaitFamily& f, int side, const Placement& root, float t,
                     const FootGeometry& g) {
  if (!f.moving) {
    FootPlant p;
    p.ankle_xz_m = root.apply(f.stand_ankle_m[side]);
    p.yaw_rad = root.heading_rad + f.stand_yaw_rad[side];
    p.lift_pitch_rad = f.style.lift_pitch_rad;
    return plant_key(p);
  }
  const float c = f.cycle_s;
  if (side == kLeft) return plant_key(neutral_plant(f, kLeft, root, t, 0.0f));
  const FootPlant before = neutral_plant(f, kRight, root, t - 0.5f * c, -0.5f);
  if (before.lift_s >= t) return plant_key(before);
  // Running: the right foot is mid-air at the boundary, on its way to the next plant.
  const FootPlant next = neutral_plant(f, kRight, root, t + 0.5f * c, 0.5f);
  const float u = (t - before.lift_s) / (next.land_s - before.lift_s);
  return via_key(via_between(before, next, t, u, g, f.style.swing.ease_exponent));
}

FootPlant path_plant(const RootPath& path, float anchor_s, vec2 offset_m, float yaw_rad) {
  const Placement r = path.at(anchor_s);
  FootPlant p;
  p.ankle_xz_m = r.apply(offset_m);
  p.yaw_rad = r.heading_rad + yaw_rad;
  return p;
}

Placement arc_end(float length_m, float turn_rad) {
  const float a = std::abs(turn_rad);
  if (a < 1e-5f) return {vec2(0.0f, length_m), 0.0f};
  const float r = length_m / a;
  const float sign = turn_rad > 0.0f ? 1.0f : -1.0f;
  return {vec2(sign * r * (1.0f - std::cos(a)), r * std::sin(a)), turn_rad};
}

LocomotionSpec cycle_spec(const std::string& name, uint32_t tags, FamilyId start,
                          FamilyId end_family, float duration_s, Placement end,
                          float start_speed_mps, float end_speed_mps, const FootGeometry& g,
                          CycleTiming timing) {
  LocomotionSpec spec;
  spec.name = name;
  spec.tags = tags;
  spec.duration_s = duration_s;
  spec.start_family = start;
  spec.end_family = end_family;
  // Transitions finish blending a little before the end so the last events (the lift-off that
  // leads into the end boundary) already use the end family's numbers.
  spec.style_blend_begin_s = 0.0f;
  spec.style_blend_end_s = start == end_family ? duration_s : 0.8f * duration_s;
  spec.path = RootPath(duration_s, end, start_speed_mps, end_speed_mps);
  const GaitFamily& fa = gait_family(start);
  const GaitFamily& fb = gait_family(end_family);
  const float t_end = duration_s;
  const Placement origin{};

  // Left: touches down at the start boundary, lifts mid-clip, touches down at the end boundary.
  FootKey l0 = boundary_key(fa, kLeft, origin, 0.0f, g);
  const float left_lift = (timing.left_lift < 0.0f ? fa.stance_fraction : timing.left_lift) * duration_s;
  l0.plant.lift_s = left_lift;
  l0.plant.heel_off_s = left_lift - fa.heel_off_fraction * duration_s;
  l0.plant.lift_pitch_rad = style_at(spec, left_lift).lift_pitch_rad;
  spec.feet[kLeft] = {l0, boundary_key(fb, kLeft, end, t_end, g)};

  // Right: from its start state (planted behind, or mid-air), one interior step, to its end state.
  const FootKey r0 = boundary_key(fa, kRight, origin, 0.0f, g);
  FootKey r1 = boundary_key(fb, kRight, end, t_end, g);
  const float land = timing.right_land * duration_s;
  if (!r1.is_via) {
    r1.plant.land_s = land;
    spec.feet[kRight] = {r0, r1};
  } else {
    const float lift = (timing.right_lift < 0.0f ? timing.right_land + fb.stance_fraction
                                                 : timing.right_lift) * duration_s;
    const float mid = 0.5f * (land + lift);
    const float w = style_weight(spec, mid);
    const vec2 offset(-lerp(fa.step_width_m, fb.step_width_m, w),
                      lerp(fa.foot_forward_m, fb.foot_forward_m, w));
    FootPlant p = path_plant(spec.path, mid, offset, -lerp(fa.toe_out_rad, fb.toe_out_rad, w));
    p.land_s = land;
    p.lift_s = lift;
    p.heel_off_s = lift - fb.heel_off_fraction * duration_s;
    p.lift_pitch_rad = style_at(spec, lift).lift_pitch_rad;
    spec.feet[kRight] = {r0, plant_key(p), r1};
  }
  return spec;
}

LocomotionSpec transition_spec(const std::string& name, uint32_t tags, FamilyId start,
                               FamilyId end_family, float duration_s, Placement end,
                               float start_speed_mps, float end_speed_mps, const FootGeometry& g) {
  LocomotionSpec spec;
  spec.name = name;
  spec.tags = tags;
  spec.duration_s = duration_s;
  spec.start_family = start;
  spec.end_family = end_family;
  spec.style_blend_begin_s = 0.0f;
  spec.style_blend_end_s = 0.85f * duration_s;
  spec.path = RootPath(duration_s, end, start_speed_mps, end_speed_mps);
  for (int side = 0; side < 2; ++side)
    spec.feet[side] = {boundary_key(gait_family(start), side, Placement{}, 0.0f, g),
                       boundary_key(gait_family(end_family), side, end, duration_s, g)};
  return spec;
}

void set_step(LocomotionSpec& spec, int side, float heel_off_s, float lift_s, float land_s) {
  FootTimeline& keys = spec.feet[side];
  FootPlant& first = keys.front().plant;
  if (lift_s >= 0.0f) {
    first.lift_s = lift_s;
    first.heel_off_s = heel_off_s;
    first.lift_pitch_rad = style_at(spec, lift_s).lift_pitch_rad;
  }
  keys.back().plant.land_s = land_s;
}

LocomotionSpec standing_spec(const std::string& name, uint32_t tags, FamilyId family,
                             float duration_s, StandingMotion motion, const FootGeometry& g) {
  LocomotionSpec spec;
  spec.name = name;
  spec.tags = tags;
  spec.duration_s = duration_s;
  spec.start_family = spec.end_family = family;
  spec.path = RootPath(duration_s, Placement{}, 0.0f, 0.0f);
  for (int side = 0; side < 2; ++side)
    spec.feet[side] = {boundary_key(gait_family(family), side, Placement{}, 0.0f, g)};
  spec.standing = motion;
  return spec;
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

  std::array<FootSample, 2> feet;
  std::array<vec2, 2> local;  // ankles in the root frame: x = side, y = forward
  float support_x = 0.0f;
  for (int side = 0; side < 2; ++side) {
    feet[side] = sample_foot(spec.feet[side], t, g, side_sign(side), style.weight_accept_s,
                             shape_at, root_at);
    local[side] = to_root.apply(ground(feet[side].ankle_m));
    support_x += feet[side].load * local[side].x;
  }
  const float fore_aft = local[kLeft].y - local[kRight].y;

  BodyPose pose;
  // Pelvis: sways over the loaded foot (loads are bells over each stance, so the sway is a smooth
  // side-to-side wave that crosses the middle at double support), twists so the leading leg's hip
  // comes forward, lists up on the loaded side.
  const float sway = style.sway_gain * support_x + sm.sway_m * std::sin(phase);
  const float twist = std::clamp(-style.twist_rad_per_m * fore_aft, -kMaxTwistRad, kMaxTwistRad);
  const float roll = style.list_rad * (feet[kLeft].load - feet[kRight].load);
  const float heading = root.heading_rad + twist;
  pose.pelvis_rot = quat_ypr(heading, style.pelvis_pitch_rad, roll);
  const vec2 pelvis_xz = root.apply(vec2(sway, -style.pelvis_back_m));
  const float nominal = style.pelvis_height_m +
                        sm.bounce_m * std::sin(phase * static_cast<float>(sm.bounce_cycles));
  pose.pelvis_m = from_ground(
      pelvis_xz, pelvis_height(skeleton, rig, style, feet, pelvis_xz, pose.pelvis_rot, nominal));

  // Trunk: the chest counter-rotates against the pelvis twist and rolls back towards level; the
  // head looks along the path.
  pose.spine_ypr_rad = vec3(style.spine_yaw_rad - (1.0f + style.counter_rotation) * twist,
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

#include "author/gait_style.hpp"

#include "author/easing.hpp"
#include "author/rig.hpp"

namespace foresight::author {
namespace {

// The numbers below were set by eye against reference gait figures: walking pelvis rotation
// +-5 deg, list +-4 deg, lateral sway ~2-3 cm, arm swing ~+-20 deg; running trunk lean ~8 deg,
// elbows ~80 deg, ankle recovery height ~0.2-0.3 m; a crouch low enough (head top < 1.15 m) to
// pass under a 1.2 m table.
GaitStyle idle_style() {
  GaitStyle s;
  s.pelvis_height_m = 0.955f;
  s.pelvis_pitch_rad = 0.03f;
  s.sway_gain = 0.25f;
  s.twist_rad = 0.05f;
  s.chest_counter_rad_per_m = 0.08f;
  s.list_rad = 0.03f;
  s.spine_pitch_rad = 0.02f;
  s.head_pitch_rad = 0.05f;
  s.arm_swing_rad_per_m = 0.4f;
  s.elbow_rad = 0.2f;
  s.lift_pitch_rad = 0.3f;
  s.weight_accept_s = 0.15f;
  s.swing = {0.05f, 1.0f, 0.05f, 0.015f};
  return s;
}

GaitStyle walk_style() {
  GaitStyle s;  // The defaults are the walk.
  s.swing = {0.06f, 1.0f, 0.15f, 0.035f};
  return s;
}

GaitStyle run_style() {
  GaitStyle s;
  s.pelvis_height_m = 0.94f;
  s.pelvis_pitch_rad = 0.12f;
  s.stance_dip_m = 0.06f;
  s.reach_fraction = 0.985f;
  s.sway_gain = 0.25f;
  s.twist_rad = 0.02f;  // Runs keep the pelvis nearly square (the shoulders turn).
  s.chest_counter_rad_per_m = 0.09f;
  s.list_rad = 0.04f;
  s.spine_pitch_rad = 0.1f;
  s.head_pitch_rad = 0.0f;
  s.arm_swing_rad_per_m = 0.45f;
  s.arm_flex_rad = 0.15f;
  s.arm_abduction_rad = 0.18f;
  s.elbow_rad = 1.4f;
  s.elbow_swing_rad_per_rad = 0.3f;
  s.lift_pitch_rad = 0.8f;
  s.weight_accept_s = 0.08f;
  s.swing = {0.22f, 1.4f, 0.1f, 0.02f};
  return s;
}

GaitStyle crouch_style() {
  GaitStyle s;
  s.pelvis_height_m = 0.53f;
  s.pelvis_back_m = 0.06f;
  s.pelvis_pitch_rad = 0.45f;
  s.sway_gain = 0.4f;
  s.twist_rad = 0.07f;
  s.chest_counter_rad_per_m = 0.04f;
  s.list_rad = 0.02f;
  s.spine_pitch_rad = 0.6f;
  s.head_pitch_rad = 0.35f;
  s.arm_swing_rad_per_m = 0.35f;
  s.arm_flex_rad = 0.35f;
  s.arm_abduction_rad = 0.2f;
  s.elbow_rad = 0.6f;
  s.elbow_swing_rad_per_rad = 0.3f;
  s.lift_pitch_rad = 0.4f;
  s.swing = {0.05f, 1.0f, 0.08f, 0.03f};
  return s;
}

GaitStyle fight_style() {
  GaitStyle s;
  s.pelvis_height_m = 0.89f;
  s.pelvis_pitch_rad = 0.1f;
  s.sway_gain = 0.5f;
  s.twist_rad = 0.0f;
  s.chest_counter_rad_per_m = 0.0f;
  s.list_rad = 0.0f;
  s.spine_pitch_rad = 0.12f;
  s.spine_yaw_rad = -0.3f;
  s.head_pitch_rad = 0.1f;
  s.arm_swing_rad_per_m = 0.0f;
  s.guard = 1.0f;
  s.clavicle_raise_rad = 0.12f;
  s.lift_pitch_rad = 0.3f;
  s.weight_accept_s = 0.15f;
  s.swing = {0.05f, 1.0f, 0.05f, 0.015f};
  return s;
}

GaitFamily make_idle() {
  GaitFamily f;
  f.id = FamilyId::kIdle;
  f.name = "idle";
  f.style = idle_style();
  return f;
}

// Walking: the pelvis midway between the feet at the strike (foot_forward = stride * (0.5 -
// stance_fraction) / 2), toes out as far as standing (so starts and stops need no pivot), heel-off
// 0.2 s before the strike: the window in which a turning step pivots its rear foot on the ball.
// Events the boundary fixes fall on whole frames (heel-off 6 frames before, lift-off 3 after), so
// a rolling foot never spends a frame half-rolled.
GaitFamily make_walk(FamilyId id, int lead) {
  GaitFamily f;
  f.id = id;
  f.name = lead == kLeft ? "walk_L" : "walk_R";
  f.style = walk_style();
  f.moving = true;
  f.lead_side = lead;
  f.cycle_s = 30.0f / 30.0f;
  f.stride_m = 1.40f;
  f.stance_fraction = 0.60f;
  f.heel_off_fraction = 0.30f;
  f.step_width_m = 0.055f;
  f.foot_forward_m = -0.07f;
  f.toe_out_rad = 0.12f;
  return f;
}

// Slow walking: shorter strides at the same cadence (1.0 m/s), a family of its own so that its
// steps stay half a second long.
GaitFamily make_slow(FamilyId id, int lead) {
  GaitFamily f = make_walk(id, lead);
  f.name = lead == kLeft ? "slow_L" : "slow_R";
  f.stride_m = 1.00f;
  f.stance_fraction = 0.62f;
  f.heel_off_fraction = 0.32f;  // Heel-off 0.2 s before the boundary, as in the walk.
  f.foot_forward_m = -0.06f;
  return f;
}

GaitFamily make_run(FamilyId id, int lead) {
  GaitFamily f;
  f.id = id;
  f.name = lead == kLeft ? "run_L" : "run_R";
  f.style = run_style();
  f.moving = true;
  f.lead_side = lead;
  f.cycle_s = 22.0f / 30.0f;
  f.stride_m = 2.20f;
  f.stance_fraction = 0.36f;
  f.heel_off_fraction = 0.18f;
  f.step_width_m = 0.06f;
  f.foot_forward_m = -0.10f;
  f.toe_out_rad = 0.05f;
  return f;
}

GaitFamily make_crouch_idle() {
  GaitFamily f;
  f.id = FamilyId::kCrouchIdle;
  f.name = "crouch_idle";
  f.style = crouch_style();
  return f;
}

GaitFamily make_crouch_walk(FamilyId id, int lead) {
  GaitFamily f;
  f.id = id;
  f.name = lead == kLeft ? "crouch_walk_L" : "crouch_walk_R";
  f.style = crouch_style();
  f.moving = true;
  f.lead_side = lead;
  f.cycle_s = 32.0f / 30.0f;
  f.stride_m = 0.80f;
  f.stance_fraction = 0.65f;
  f.heel_off_fraction = 0.3375f;  // Heel-off 0.2 s (6 frames) before the boundary.
  f.step_width_m = 0.10f;
  f.foot_forward_m = -0.06f;
  f.toe_out_rad = 0.12f;
  return f;
}

GaitFamily make_fight() {
  GaitFamily f;
  f.id = FamilyId::kFight;
  f.name = "fight_stance";
  f.style = fight_style();
  // Orthodox stance: left foot leads, turned slightly in; right foot back, turned out.
  f.stand_ankle_m = {vec2(0.12f, 0.21f), vec2(-0.15f, -0.21f)};
  f.stand_yaw_rad = {-0.2f, -0.55f};
  return f;
}

}  // namespace

GaitStyle mix(const GaitStyle& a, const GaitStyle& b, float w) {
  GaitStyle o;
  o.pelvis_height_m = lerp(a.pelvis_height_m, b.pelvis_height_m, w);
  o.pelvis_back_m = lerp(a.pelvis_back_m, b.pelvis_back_m, w);
  o.pelvis_pitch_rad = lerp(a.pelvis_pitch_rad, b.pelvis_pitch_rad, w);
  o.stance_dip_m = lerp(a.stance_dip_m, b.stance_dip_m, w);
  o.reach_fraction = lerp(a.reach_fraction, b.reach_fraction, w);
  o.sway_gain = lerp(a.sway_gain, b.sway_gain, w);
  o.twist_rad = lerp(a.twist_rad, b.twist_rad, w);
  o.list_rad = lerp(a.list_rad, b.list_rad, w);
  o.spine_pitch_rad = lerp(a.spine_pitch_rad, b.spine_pitch_rad, w);
  o.spine_yaw_rad = lerp(a.spine_yaw_rad, b.spine_yaw_rad, w);
  o.chest_counter_rad_per_m = lerp(a.chest_counter_rad_per_m, b.chest_counter_rad_per_m, w);
  o.head_pitch_rad = lerp(a.head_pitch_rad, b.head_pitch_rad, w);
  o.arm_swing_rad_per_m = lerp(a.arm_swing_rad_per_m, b.arm_swing_rad_per_m, w);
  o.arm_flex_rad = lerp(a.arm_flex_rad, b.arm_flex_rad, w);
  o.arm_abduction_rad = lerp(a.arm_abduction_rad, b.arm_abduction_rad, w);
  o.elbow_rad = lerp(a.elbow_rad, b.elbow_rad, w);
  o.elbow_swing_rad_per_rad = lerp(a.elbow_swing_rad_per_rad, b.elbow_swing_rad_per_rad, w);
  o.guard = lerp(a.guard, b.guard, w);
  o.clavicle_raise_rad = lerp(a.clavicle_raise_rad, b.clavicle_raise_rad, w);
  o.lift_pitch_rad = lerp(a.lift_pitch_rad, b.lift_pitch_rad, w);
  o.weight_accept_s = lerp(a.weight_accept_s, b.weight_accept_s, w);
  o.swing.height_m = lerp(a.swing.height_m, b.swing.height_m, w);
  o.swing.ease_exponent = lerp(a.swing.ease_exponent, b.swing.ease_exponent, w);
  o.swing.toe_up_rad = lerp(a.swing.toe_up_rad, b.swing.toe_up_rad, w);
  o.swing.bow_m = lerp(a.swing.bow_m, b.swing.bow_m, w);
  return o;
}

const GaitFamily& gait_family(FamilyId id) {
  static const std::array<GaitFamily, kNumFamilies> families = {
      make_idle(),
      make_walk(FamilyId::kWalkL, kLeft), make_walk(FamilyId::kWalkR, kRight),
      make_slow(FamilyId::kSlowL, kLeft), make_slow(FamilyId::kSlowR, kRight),
      make_run(FamilyId::kRunL, kLeft), make_run(FamilyId::kRunR, kRight),
      make_crouch_idle(),
      make_crouch_walk(FamilyId::kCrouchWalkL, kLeft),
      make_crouch_walk(FamilyId::kCrouchWalkR, kRight),
      make_fight()};
  return families[static_cast<size_t>(id)];
}

FamilyId strike_family(FamilyId gait, int lead_side) {
  const bool left = lead_side == kLeft;
  switch (gait) {
    case FamilyId::kWalkL: case FamilyId::kWalkR:
      return left ? FamilyId::kWalkL : FamilyId::kWalkR;
    case FamilyId::kSlowL: case FamilyId::kSlowR:
      return left ? FamilyId::kSlowL : FamilyId::kSlowR;
    case FamilyId::kRunL: case FamilyId::kRunR:
      return left ? FamilyId::kRunL : FamilyId::kRunR;
    case FamilyId::kCrouchWalkL: case FamilyId::kCrouchWalkR:
      return left ? FamilyId::kCrouchWalkL : FamilyId::kCrouchWalkR;
    default:
      return gait;
  }
}

vec3 guard_wrist_m(int side) {
  // Fists in front of the chin: the lead (left) hand further out, the rear hand by the cheek.
  const float s = side_sign(side);
  return side == kLeft ? vec3(-s * 0.10f, 0.10f, 0.28f) : vec3(-s * 0.11f, 0.12f, 0.20f);
}

vec3 guard_elbow_dir(int side) {
  return glm::normalize(vec3(side_sign(side) * 0.25f, -1.0f, 0.0f));
}

}  // namespace foresight::author

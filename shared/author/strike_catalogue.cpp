// The default strikes, as parameters of the punch and kick generators (fight_moves.cpp).
// Targets are in the stance's root frame (facing +Z, left = +X, lead foot = left). Heights follow
// the bands the fighter uses to pick a move: low 0.5-0.8 m, mid 1.0-1.3 m, high 1.5-1.75 m; the
// reach of every target was checked against the limbs (arm 0.54 m to the wrist, leg 0.84 m to the
// ankle) with the body layer applied, so the IK meets it at the hit frame.
#include "author/fight_moves.hpp"

namespace foresight::author {
namespace {

constexpr float kPunchS = 24.0f / kFps;
constexpr float kKickS = 45.0f / kFps;

// Punch targets: (side, height); how far forward follows from the arm's extension.
StrikeSpec punch(const char* name, int side, const char* height, vec2 target, float hit_frames) {
  StrikeSpec s;
  s.name = name;
  s.kind = "punch";
  s.side = side;
  s.height = height;
  s.target_m = vec3(target, 0.0f);
  s.duration_s = kPunchS;
  s.hit_s = hit_frames / kFps;
  return s;
}

StrikeSpec kick(const char* name, int side, const char* height, vec3 target, vec3 chamber) {
  StrikeSpec s;
  s.name = name;
  s.kind = "kick";
  s.side = side;
  s.height = height;
  s.target_m = target;
  s.chamber_m = chamber;
  s.duration_s = kKickS;
  s.hit_s = 18.0f / kFps;
  return s;
}

// Lead (left) hand: jabs turn the shoulders further into the blade and step the weight forward.
std::vector<StrikeSpec> left_punches() {
  std::vector<StrikeSpec> v;
  StrikeSpec s = punch("punch_left_jab_high", kLeft, "high", vec2(0.03f, 1.55f), 7);
  s.pelvis_shift_m = vec3(0, 0, 0.10f);
  s.pelvis_ypr_rad = vec3(-0.25f, 0, 0);
  s.spine_ypr_rad = vec3(-0.25f, 0.05f, 0);
  s.elbow_dir_hit = vec3(0.4f, -1, -0.2f);
  v.push_back(s);

  s = punch("punch_left_jab_mid", kLeft, "mid", vec2(0.04f, 1.15f), 7);
  s.pelvis_shift_m = vec3(0, -0.05f, 0.10f);
  s.pelvis_ypr_rad = vec3(-0.25f, 0.05f, 0);
  s.spine_ypr_rad = vec3(-0.25f, 0.2f, 0);
  s.elbow_dir_hit = vec3(0.4f, -1, -0.2f);
  v.push_back(s);

  s = punch("punch_left_jab_low", kLeft, "low", vec2(0.05f, 0.74f), 8);
  s.pelvis_shift_m = vec3(0, -0.2f, 0.08f);
  s.pelvis_ypr_rad = vec3(-0.2f, 0.15f, 0);
  s.spine_ypr_rad = vec3(-0.2f, 0.45f, 0);
  s.elbow_dir_hit = vec3(0.4f, -0.6f, -0.5f);
  v.push_back(s);

  s = punch("punch_left_hook_high", kLeft, "high", vec2(-0.02f, 1.50f), 8);
  s.hook_via_m = vec3(0.42f, 1.42f, 0.35f);
  s.arm_extension = 0.75f;
  s.pelvis_shift_m = vec3(0, -0.02f, 0.05f);
  s.pelvis_ypr_rad = vec3(-0.35f, 0, 0);
  s.spine_ypr_rad = vec3(-0.45f, 0.05f, 0);
  s.elbow_dir_hit = vec3(1, 0.15f, 0);
  v.push_back(s);
  return v;
}

// Rear (right) hand: the hips and shoulders turn through, the rear foot rolls onto its ball and
// pivots in.
std::vector<StrikeSpec> right_punches() {
  std::vector<StrikeSpec> v;
  StrikeSpec s = punch("punch_right_cross_high", kRight, "high", vec2(-0.02f, 1.55f), 8);
  s.pelvis_shift_m = vec3(0, 0, 0.10f);
  s.pelvis_ypr_rad = vec3(0.45f, 0, 0);
  s.spine_ypr_rad = vec3(0.45f, 0.05f, 0);
  s.elbow_dir_hit = vec3(-0.4f, -1, -0.2f);
  s.pivot_foot = kRight;
  s.support_heel_rad = 0.45f;
  s.support_pivot_rad = 0.5f;
  v.push_back(s);

  s = punch("punch_right_cross_mid", kRight, "mid", vec2(-0.03f, 1.15f), 8);
  s.pelvis_shift_m = vec3(0, -0.05f, 0.10f);
  s.pelvis_ypr_rad = vec3(0.45f, 0.05f, 0);
  s.spine_ypr_rad = vec3(0.4f, 0.2f, 0);
  s.elbow_dir_hit = vec3(-0.4f, -1, -0.2f);
  s.pivot_foot = kRight;
  s.support_heel_rad = 0.45f;
  s.support_pivot_rad = 0.5f;
  v.push_back(s);

  s = punch("punch_right_cross_low", kRight, "low", vec2(-0.04f, 0.74f), 9);
  s.pelvis_shift_m = vec3(0, -0.2f, 0.08f);
  s.pelvis_ypr_rad = vec3(0.4f, 0.15f, 0);
  s.spine_ypr_rad = vec3(0.35f, 0.45f, 0);
  s.elbow_dir_hit = vec3(-0.4f, -0.6f, -0.5f);
  s.pivot_foot = kRight;
  s.support_heel_rad = 0.4f;
  s.support_pivot_rad = 0.4f;
  v.push_back(s);

  s = punch("punch_right_hook_high", kRight, "high", vec2(0.02f, 1.50f), 9);
  s.hook_via_m = vec3(-0.45f, 1.42f, 0.30f);
  s.arm_extension = 0.75f;
  s.pelvis_ypr_rad = vec3(0.5f, 0, 0);
  s.spine_ypr_rad = vec3(0.5f, 0.05f, 0);
  s.elbow_dir_hit = vec3(-1, 0.15f, 0);
  s.pivot_foot = kRight;
  s.support_heel_rad = 0.4f;
  s.support_pivot_rad = 0.5f;
  v.push_back(s);
  return v;
}

std::vector<StrikeSpec> kicks(int side) {
  // One recipe per kick, mirrored through x = 0 for the other leg (the stance is not symmetric,
  // but targets are relative to the pelvis at the hit and chambers to the hip, so the same numbers
  // work for the lead and the rear leg).
  const float m = side_sign(side);
  const std::string p = side == kLeft ? "kick_left_" : "kick_right_";
  std::vector<StrikeSpec> v;

  // Front kicks: knee up in the sagittal plane, then the leg snaps out, striking with the ball of
  // the foot (toes pulled back); the higher the target, the more the pelvis tucks and the trunk
  // leans back, and the support foot rises onto its ball.
  StrikeSpec s = kick((p + "front_low").c_str(), side, "low", vec3(m * 0.08f, 0.62f, 0.75f),
                      vec3(0, -0.45f, 0.30f));
  s.pelvis_ypr_rad = vec3(0, -0.05f, 0);
  s.spine_ypr_rad = vec3(0, -0.05f, 0);
  s.toe_bend_hit_rad = -0.5f;
  v.push_back(s);

  s = kick((p + "front_mid").c_str(), side, "mid", vec3(m * 0.07f, 1.12f, 0.72f),
           vec3(0, -0.30f, 0.32f));
  s.pelvis_shift_m = vec3(0, 0.03f, -0.03f);
  s.pelvis_ypr_rad = vec3(0, -0.2f, 0);
  s.spine_ypr_rad = vec3(0, -0.1f, 0);
  s.support_heel_rad = 0.15f;
  s.toe_bend_hit_rad = -0.5f;
  v.push_back(s);

  s = kick((p + "front_high").c_str(), side, "high", vec3(m * 0.06f, 1.53f, 0.55f),
           vec3(0, -0.12f, 0.25f));
  s.pelvis_shift_m = vec3(0, 0.09f, -0.03f);
  s.pelvis_ypr_rad = vec3(0, -0.4f, 0);
  s.spine_ypr_rad = vec3(0, -0.2f, 0);
  s.support_heel_rad = 0.35f;
  s.toe_bend_hit_rad = -0.5f;
  v.push_back(s);

  // Roundhouse: the hips turn over (the support foot pivots on its ball), the knee comes round in
  // a horizontal plane and the shin snaps through with the foot pointed (instep strike).
  s = kick((p + "roundhouse_mid").c_str(), side, "mid", vec3(m * 0.02f, 1.20f, 0.75f),
           vec3(m * 0.40f, -0.05f, 0.15f));
  s.knee_axis = vec3(0, m, 0);
  s.pelvis_ypr_rad = vec3(-m * 1.1f, -0.1f, m * 0.35f);
  s.spine_ypr_rad = vec3(m * 0.5f, -0.05f, -m * 0.3f);
  s.support_heel_rad = 0.35f;
  s.support_pivot_rad = -m * 1.0f;
  s.ankle_point_rad = 1.1f;
  v.push_back(s);
  return v;
}

}  // namespace

std::vector<StrikeSpec> default_strikes() {
  std::vector<StrikeSpec> v = left_punches();
  for (const StrikeSpec& s : right_punches()) v.push_back(s);
  for (int side = 0; side < 2; ++side)
    for (const StrikeSpec& s : kicks(side)) v.push_back(s);
  return v;
}

}  // namespace foresight::author

#include "author/fight_moves.hpp"

#include "author/easing.hpp"
#include "author/key_track.hpp"
#include "author/standing_specs.hpp"
#include "graph/motion_graph.hpp"

#include <algorithm>
#include <cmath>

namespace foresight::author {
namespace {

constexpr float kFrameS = 1.0f / kFps;
// Fraction of the way from the pelvis to the support foot the pelvis travels before a kick.
constexpr float kKickWeightShift = 0.7f;

// A weight that rises from 0 to 1 at `peak_s`, holds `hold_s`, and falls back to 0 by `back_s`,
// easing in and out at each key.
KeyTrack<float> pulse(float start_s, float peak_s, float hold_s, float back_s, float end_s) {
  KeyTrack<float> k;
  k.key(0.0f, 0.0f, true);
  if (start_s > 0.0f) k.key(start_s, 0.0f, true);
  k.key(peak_s, 1.0f, true).key(peak_s + hold_s, 1.0f, true).key(back_s, 0.0f, true);
  if (end_s > back_s) k.key(end_s, 0.0f, true);
  return k;
}

// Rolls a planted foot onto its ball by heel_rad and pivots it about the ball by pivot_rad; the ball
// stays where it was.
void pivot_on_ball(FootPose& foot, const FootGeometry& g, float heel_rad, float pivot_rad) {
  const float yaw = heading_of(foot.rot * vec3(0, 0, 1));
  const vec3 ball = foot.ankle_m + quat_ypr(yaw, 0.0f, 0.0f) * g.ball_from_ankle_m;
  foot.rot = quat_ypr(yaw + pivot_rad, heel_rad, 0.0f);
  foot.ankle_m = ball + foot.rot * -g.ball_from_ankle_m;
  foot.toe_bend_rad = -heel_rad;
}

// Lowers the pelvis (softly) until the given legs reach their ankles; the same rule as the gait.
void keep_legs_in_reach(const Skeleton& s, const Rig& rig, BodyPose& pose,
                        std::array<bool, 2> legs, float reach_fraction) {
  const float reach = reach_fraction * (rig.leg[kLeft].upper_m + rig.leg[kLeft].lower_m);
  for (int side = 0; side < 2; ++side) {
    if (!legs[side]) continue;
    const vec3 hip_rel = pose.pelvis_rot * s.rest_offsets_m[rig.leg[side].root];
    const vec3 ankle = pose.feet[side].ankle_m;
    const float d = glm::length(ground(pose.pelvis_m + hip_rel) - ground(ankle));
    if (d >= reach) continue;
    const float highest = ankle.y - hip_rel.y + std::sqrt(reach * reach - d * d);
    pose.pelvis_m.y = soft_min(pose.pelvis_m.y, highest, 0.03f);
  }
}

// Where the pelvis goes at the hit: the stance pelvis, shifted over the support foot (kicks) and by
// the strike's own layer.
vec3 pelvis_at_hit(const BodyPose& stance, const StrikeSpec& st) {
  vec3 p = stance.pelvis_m + st.pelvis_shift_m;
  if (st.kind == "kick") {
    const vec3 to_support = stance.feet[1 - st.side].ankle_m - stance.pelvis_m;
    p += vec3(to_support.x, 0.0f, to_support.z) * kKickWeightShift;
  }
  return p;
}

void apply_body_layer(BodyPose& pose, const StrikeSpec& st, float w) {
  const float base_pitch = gait_family(FamilyId::kFight).style.pelvis_pitch_rad;
  pose.pelvis_m += st.pelvis_shift_m * w;
  pose.pelvis_rot = quat_ypr(st.pelvis_ypr_rad.x * w, base_pitch + st.pelvis_ypr_rad.y * w,
                             st.pelvis_ypr_rad.z * w);
  pose.spine_ypr_rad += st.spine_ypr_rad * w;
}

// A punch's body: the stance with the layer at weight w (lunge, hips and shoulders turning, the
// rear foot pivoting), legs kept in reach.
BodyPose punch_body(const Skeleton& s, const Rig& rig, const FootGeometry& g, const StrikeSpec& st,
                    float w) {
  BodyPose pose = stance_pose(s, rig, g);
  apply_body_layer(pose, st, w);
  if (st.pivot_foot >= 0)
    pivot_on_ball(pose.feet[st.pivot_foot], g, st.support_heel_rad * w, st.support_pivot_rad * w);
  keep_legs_in_reach(s, rig, pose, {true, true}, 0.99f);
  return pose;
}

vec3 resolve_target(const Skeleton& s, const Rig& rig, const FootGeometry& g, const StrikeSpec& st) {
  const BodyPose stance = stance_pose(s, rig, g);
  if (st.kind == "kick")
    return vec3(st.target_m.x, st.target_m.y, pelvis_at_hit(stance, st).z + st.target_m.z);
  // Punches: as far forward of the shoulder (where it is at the hit) as arm_extension allows.
  const vec3 shoulder = torso_frame(s, rig, punch_body(s, rig, g, st, 1.0f)).shoulder_m[st.side];
  const float reach = st.arm_extension * (rig.arm[st.side].upper_m + rig.arm[st.side].lower_m);
  const vec2 side_up(st.target_m.x - shoulder.x, st.target_m.y - shoulder.y);
  const float forward = std::sqrt(std::max(0.0f, reach * reach - glm::dot(side_up, side_up)));
  return vec3(st.target_m.x, st.target_m.y, shoulder.z + forward);
}

BodyPose punch_pose(const Skeleton& s, const Rig& rig, const FootGeometry& g, const StrikeSpec& st,
                    float t) {
  const vec3 target = resolve_target(s, rig, g, st);
  const float hit = st.hit_s, hold = 2.0f * kFrameS;
  const float arm_back = hit + 0.5f * (st.duration_s - hit);
  const float body_back = hit + 0.8f * (st.duration_s - hit);
  const float arm = pulse(0.0f, hit, hold, arm_back, st.duration_s).at(t);
  const float body = pulse(0.0f, hit, hold, body_back, st.duration_s).at(t);
  BodyPose pose = punch_body(s, rig, g, st, body);

  // The fist travels from the guard (carried by the turning chest) to the target in clip space.
  const TorsoFrame torso = torso_frame(s, rig, pose);
  const int side = st.side;
  const vec3 shoulder = torso.shoulder_m[side];
  const vec3 guard = shoulder + torso.chest_rot * pose.arms[side].wrist_m;
  vec3 wrist = lerp(guard, target, arm);
  if (st.hook_via_m && t <= hit) {  // Hooks swing out and round; they come back straight.
    const vec3 via = *st.hook_via_m;
    wrist = guard * ((1 - arm) * (1 - arm)) + via * (2 * arm * (1 - arm)) + target * (arm * arm);
  }
  const quat to_chest = glm::inverse(torso.chest_rot);
  pose.arms[side].wrist_m = to_chest * (wrist - shoulder);
  pose.arms[side].elbow_dir =
      lerp(pose.arms[side].elbow_dir, to_chest * glm::normalize(st.elbow_dir_hit), arm);
  return pose;
}

BodyPose kick_pose(const Skeleton& s, const Rig& rig, const FootGeometry& g, const StrikeSpec& st,
                   float t) {
  BodyPose pose = stance_pose(s, rig, g);
  const vec3 target = resolve_target(s, rig, g, st);
  const int kick = st.side, support = 1 - st.side;
  const float T = st.duration_s, hit = st.hit_s, hold = 2.0f * kFrameS;
  const float lift = 0.1f, chamber = hit - 0.2f, rechamber = hit + hold + 0.18f;
  const float land = T - 0.3f, pre_land = land - 0.1f;

  // Weight over the support foot first, then the body layer peaking at the hit.
  const float shift = pulse(0.0f, lift, land - lift, T - 0.06f, T).at(t);
  KeyTrack<float> body_track;
  body_track.key(0.0f, 0.0f, true).key(lift, 0.0f, true).key(chamber, 0.45f).key(hit, 1.0f, true)
      .key(hit + hold, 1.0f, true).key(rechamber, 0.45f).key(land, 0.05f).key(T, 0.0f, true);
  const float body = body_track.at(t);

  const vec3 stance_pelvis = pose.pelvis_m;
  const vec3 to_support = pose.feet[support].ankle_m - stance_pelvis;
  pose.pelvis_m += vec3(to_support.x, 0.0f, to_support.z) * (kKickWeightShift * shift);
  apply_body_layer(pose, st, body);
  pivot_on_ball(pose.feet[support], g, st.support_heel_rad * body, st.support_pivot_rad * body);

  // The kicking foot: planted -> lifted -> chamber -> target (held) -> chamber -> planted. The
  // chamber hangs off the hip where it is about then (weight over the support foot, body layer
  // part-way in).
  const vec3 hip_offset = s.rest_offsets_m[rig.leg[kick].root];
  const vec3 chamber_at = stance_pelvis + vec3(to_support.x, 0.0f, to_support.z) * kKickWeightShift +
                          st.pelvis_shift_m * 0.45f + hip_offset + st.chamber_m;
  FootPose& foot = pose.feet[kick];
  const vec3 planted = foot.ankle_m;
  KeyTrack<vec3> ankle;
  // Lift-off goes straight to the chamber (the spline stays monotone: no backwards dip at the
  // floor); the set-down pauses a hand's breadth above the spot and lowers the foot vertically.
  ankle.key(0.0f, planted, true).key(lift, planted, true)
      .key(chamber, chamber_at).key(hit, target, true).key(hit + hold, target, true)
      .key(rechamber, chamber_at).key(pre_land, planted + vec3(0, 0.08f, 0), true)
      .key(land, planted, true).key(T, planted, true);
  // The foot follows the shin only well clear of the floor: flat again before the set-down.
  const float follow = pulse(lift, chamber, rechamber - chamber, pre_land, T).at(t);
  const float extend = pulse(chamber, hit, hold, rechamber, T).at(t);
  foot.ankle_m = ankle.at(t);
  // Knee: from the stance's forward knee to the kick's hinge plane while the foot is up.
  const vec3 hip = torso_frame(s, rig, pose).hip_m[kick];
  const vec3 leg = foot.ankle_m - hip;
  const vec3 hinge_knee = glm::cross(leg, st.knee_axis);
  if (glm::length(hinge_knee) > 1e-4f)
    foot.knee_dir = glm::normalize(lerp(foot.knee_dir, glm::normalize(hinge_knee), follow));
  // Foot orientation: follows the shin in the air, extending (pointing) into the hit.
  foot.shin_local_rot = glm::angleAxis(st.ankle_point_rad * extend, vec3(1, 0, 0));
  foot.shin_local_weight = follow;
  foot.toe_bend_rad = st.toe_bend_hit_rad * extend;
  // Never through the floor (the lift and set-down keys pass close to it).
  const float yaw = heading_of(foot.rot * vec3(0, 0, 1));
  const float clearance = sole_clearance(g, foot.ankle_m, yaw, 0.0f, 0.0f);
  if (follow < 0.5f && clearance < 0.0f) foot.ankle_m.y -= clearance;

  // The support leg must reach; the kicking leg too while its foot is low.
  const bool kick_low = foot.ankle_m.y < pose.pelvis_m.y - 0.4f;
  std::array<bool, 2> legs{};
  legs[support] = true;
  legs[kick] = kick_low;
  keep_legs_in_reach(s, rig, pose, legs, 0.99f);

  // The arm on the kicking side drops a little for balance.
  pose.arms[kick].wrist_m += vec3(0.0f, -0.12f, -0.08f) * body;
  return pose;
}

}  // namespace

LocomotionSpec fight_stance_spec(const FootGeometry& g) {
  // A short loop (the fighter can strike at every boundary): one light bounce on the balls of the
  // feet, a boxer's 2.5 Hz.
  StandingMotion m;
  m.bounce_m = 0.008f;
  m.bounce_cycles = 1;
  return standing_spec("fight_stance", kTagFight, FamilyId::kFight, 12.0f / kFps, m, g);
}

BodyPose stance_pose(const Skeleton& s, const Rig& rig, const FootGeometry& g) {
  const LocomotionSpec still = standing_spec("stance", kTagFight, FamilyId::kFight, 1.0f, {}, g);
  return gait_pose(s, rig, still, 0.0f);
}

LocomotionSpec idle_to_stance_spec(const FootGeometry& g) {
  // Left foot steps forward, then the right foot steps back and turns out; the guard comes up.
  LocomotionSpec spec = transition_spec("idle_to_stance", kTagFight, FamilyId::kIdle,
                                        FamilyId::kFight, 24.0f / kFps, Placement{}, g);
  set_step(spec, kLeft, 0.04f, 0.16f, 0.40f);
  set_step(spec, kRight, 0.30f, 0.42f, 0.62f);
  return spec;
}

LocomotionSpec stance_to_idle_spec(const FootGeometry& g) {
  LocomotionSpec spec = transition_spec("stance_to_idle", kTagFight, FamilyId::kFight,
                                        FamilyId::kIdle, 24.0f / kFps, Placement{}, g);
  set_step(spec, kRight, 0.04f, 0.16f, 0.40f);
  set_step(spec, kLeft, 0.30f, 0.42f, 0.62f);
  return spec;
}

BodyPose strike_pose(const Skeleton& s, const Rig& rig, const FootGeometry& g,
                     const StrikeSpec& strike, float t) {
  return strike.kind == "kick" ? kick_pose(s, rig, g, strike, t) : punch_pose(s, rig, g, strike, t);
}

Clip bake_strike(const Skeleton& s, const Rig& rig, const FootGeometry& g, const StrikeSpec& strike) {
  const int frames = static_cast<int>(std::lround(strike.duration_s * kFps)) + 1;
  return bake_clip(s, rig, strike.name, frames, kFps,
                   [&](float t) { return strike_pose(s, rig, g, strike, t); });
}

vec3 strike_target(const Skeleton& s, const Rig& rig, const FootGeometry& g, const StrikeSpec& st) {
  return resolve_target(s, rig, g, st);
}

int strike_hit_frame(const StrikeSpec& strike) {
  return static_cast<int>(std::lround(strike.hit_s * kFps));
}

}  // namespace foresight::author

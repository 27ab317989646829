#include "author/body_pose.hpp"

#include "author/easing.hpp"
#include "author/two_bone_ik.hpp"

#include <cassert>

namespace foresight::author {
namespace {

// Shares of the chest's bend taken by Spine, Spine1 and Chest: the lower back bends a little
// less than the thoracic spine.
constexpr float kSpineShare[3] = {0.30f, 0.35f, 0.35f};
constexpr float kNeckShare = 0.4f;

FootPose mix(const FootPose& a, const FootPose& b, float w) {
  FootPose o;
  o.ankle_m = lerp(a.ankle_m, b.ankle_m, w);
  o.rot = glm::slerp(a.rot, b.rot, w);
  o.toe_bend_rad = lerp(a.toe_bend_rad, b.toe_bend_rad, w);
  o.knee_dir = lerp(a.knee_dir, b.knee_dir, w);
  o.shin_local_rot = glm::slerp(a.shin_local_rot, b.shin_local_rot, w);
  o.shin_local_weight = lerp(a.shin_local_weight, b.shin_local_weight, w);
  return o;
}

ArmPose mix(const ArmPose& a, const ArmPose& b, float w) {
  return {lerp(a.wrist_m, b.wrist_m, w), lerp(a.elbow_dir, b.elbow_dir, w),
          lerp(a.wrist_flex_rad, b.wrist_flex_rad, w)};
}

quat clavicle_rot(vec2 raise_protract_rad, int side) {
  // Left clavicle points +X: +Z rotation raises it, -Y rotation brings it forward; the right one
  // mirrors both.
  const float s = side_sign(side);
  return glm::angleAxis(-s * raise_protract_rad.y, vec3(0, 1, 0)) *
         glm::angleAxis(s * raise_protract_rad.x, vec3(0, 0, 1));
}

}  // namespace

BodyPose mix(const BodyPose& a, const BodyPose& b, float w) {
  BodyPose o;
  o.pelvis_m = lerp(a.pelvis_m, b.pelvis_m, w);
  o.pelvis_rot = glm::slerp(a.pelvis_rot, b.pelvis_rot, w);
  o.spine_ypr_rad = lerp(a.spine_ypr_rad, b.spine_ypr_rad, w);
  o.head_rot = glm::slerp(a.head_rot, b.head_rot, w);
  for (int s = 0; s < 2; ++s) {
    o.clavicle_rad[s] = lerp(a.clavicle_rad[s], b.clavicle_rad[s], w);
    o.arms[s] = mix(a.arms[s], b.arms[s], w);
    o.feet[s] = mix(a.feet[s], b.feet[s], w);
  }
  return o;
}

quat spine_joint_rot(vec3 ypr, float share) {
  return quat_ypr(ypr.x * share, ypr.y * share, ypr.z * share);
}

TorsoFrame torso_frame(const Skeleton& s, const Rig& rig, const BodyPose& pose) {
  TorsoFrame t;
  vec3 p = pose.pelvis_m;
  quat q = pose.pelvis_rot;
  for (int side = 0; side < 2; ++side) t.hip_m[side] = p + q * s.rest_offsets_m[rig.leg[side].root];
  for (int i = 0; i < 3; ++i) {
    p += q * s.rest_offsets_m[rig.spine[i]];
    q = q * spine_joint_rot(pose.spine_ypr_rad, kSpineShare[i]);
  }
  t.chest_m = p;
  t.chest_rot = q;
  for (int side = 0; side < 2; ++side) {
    const vec3 clav = p + q * s.rest_offsets_m[rig.clavicle[side]];
    const quat clav_rot = q * clavicle_rot(pose.clavicle_rad[side], side);
    t.shoulder_m[side] = clav + clav_rot * s.rest_offsets_m[rig.arm[side].root];
  }
  return t;
}

void solve_body_pose(const Skeleton& s, const Rig& rig, const BodyPose& pose,
                     std::span<vec3> local_pos_m, std::span<quat> local_rot) {
  const int n = s.num_joints();
  assert(static_cast<int>(local_pos_m.size()) >= n && static_cast<int>(local_rot.size()) >= n);
  for (int j = 0; j < n; ++j) {
    local_pos_m[j] = s.rest_offsets_m[j];
    local_rot[j] = quat(1, 0, 0, 0);
  }
  local_pos_m[rig.hips] = pose.pelvis_m;
  local_rot[rig.hips] = glm::normalize(pose.pelvis_rot);

  // Torso: the spine bend spread over three joints.
  quat chest_rot = local_rot[rig.hips];
  for (int i = 0; i < 3; ++i) {
    local_rot[rig.spine[i]] = spine_joint_rot(pose.spine_ypr_rad, kSpineShare[i]);
    chest_rot = chest_rot * local_rot[rig.spine[i]];
  }
  // Head: aim in clip space, shared between neck and head.
  const quat rel = glm::normalize(glm::inverse(chest_rot) * pose.head_rot);
  const quat neck = glm::slerp(quat(1, 0, 0, 0), rel, kNeckShare);
  local_rot[rig.neck] = neck;
  local_rot[rig.head] = glm::normalize(glm::inverse(neck) * rel);

  const TorsoFrame torso = torso_frame(s, rig, pose);
  for (int side = 0; side < 2; ++side) {
    // Arms: wrist and elbow direction given in chest axes, relative to the shoulder joint.
    const quat clav_local = clavicle_rot(pose.clavicle_rad[side], side);
    local_rot[rig.clavicle[side]] = clav_local;
    const ArmPose& arm = pose.arms[side];
    const LimbRig& al = rig.arm[side];
    const vec3 shoulder = torso.shoulder_m[side];
    const TwoBoneSolution a =
        solve_two_bone(shoulder, shoulder + torso.chest_rot * arm.wrist_m, al.upper_m, al.lower_m,
                       torso.chest_rot * arm.elbow_dir, HingeSide::kElbow);
    const quat clav_global = torso.chest_rot * clav_local;
    local_rot[al.root] = glm::normalize(glm::inverse(clav_global) * a.upper_global);
    local_rot[al.mid] = a.lower_local;
    local_rot[al.end] = glm::angleAxis(-arm.wrist_flex_rad, vec3(1, 0, 0));

    // Legs: ankle target and knee direction in clip space; the foot keeps its clip-space
    // orientation (or its shin-relative one for kicks).
    const FootPose& foot = pose.feet[side];
    const LimbRig& ll = rig.leg[side];
    const TwoBoneSolution l = solve_two_bone(torso.hip_m[side], foot.ankle_m, ll.upper_m,
                                             ll.lower_m, foot.knee_dir, HingeSide::kKnee);
    local_rot[ll.root] = glm::normalize(glm::inverse(local_rot[rig.hips]) * l.upper_global);
    local_rot[ll.mid] = l.lower_local;
    const quat shin_global = l.upper_global * l.lower_local;
    const quat foot_global =
        glm::slerp(glm::normalize(foot.rot), shin_global * foot.shin_local_rot,
                   foot.shin_local_weight);
    local_rot[ll.end] = glm::normalize(glm::inverse(shin_global) * foot_global);
    local_rot[rig.toe[side]] = glm::angleAxis(foot.toe_bend_rad, vec3(1, 0, 0));
  }
}

Clip bake_clip(const Skeleton& s, const Rig& rig, const std::string& name, int num_frames,
               float fps, const std::function<BodyPose(float)>& pose_at) {
  Clip clip;
  clip.name = name;
  clip.fps = fps;
  clip.resize(s, num_frames);
  for (int f = 0; f < num_frames; ++f) {
    solve_body_pose(s, rig, pose_at(static_cast<float>(f) / fps), clip.frame_pos(f),
                    clip.frame_rot(f));
    if (f == 0) continue;
    // Same hemisphere as the previous frame: q and -q are the same rotation, but a naive blend
    // between opposite signs takes the long way round.
    const auto prev = clip.frame_rot(f - 1);
    auto cur = clip.frame_rot(f);
    for (int j = 0; j < clip.num_joints; ++j)
      if (glm::dot(prev[j], cur[j]) < 0.0f) cur[j] = -cur[j];
  }
  return clip;
}

}  // namespace foresight::author

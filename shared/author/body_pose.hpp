#pragma once
// BodyPose: a frame described by what an animator keys (pelvis, spine bend, head aim, where the
// hands and feet go) rather than by joint rotations. solve_body_pose turns it into the skeleton's
// local rotations with two-bone IK for the limbs; every default clip is baked through it, so two
// clips whose BodyPoses agree at a boundary produce the same skeleton pose there.
#include "author/rig.hpp"
#include "anim/clip.hpp"

#include <array>
#include <functional>
#include <span>
#include <string>

namespace foresight::author {

struct FootPose {
  vec3 ankle_m{0.0f};         ///< Clip space.
  quat rot{1, 0, 0, 0};       ///< Clip-space foot orientation (identity: flat, toes along +Z).
  float toe_bend_rad = 0.0f;  ///< ToeBase about its X; negative bends the toes up.
  vec3 knee_dir{0, 0, 1};     ///< Clip-space direction the knee should point.
  /// Foot orientation relative to the shin, used with this weight instead of `rot` (kicks: the
  /// foot follows the leg).
  quat shin_local_rot{1, 0, 0, 0};
  float shin_local_weight = 0.0f;
};

struct ArmPose {
  vec3 wrist_m{0, -0.54f, 0};  ///< Wrist relative to the shoulder joint (Arm), in chest axes.
  vec3 elbow_dir{0, 0, -1};    ///< Where the elbow should point, chest axes.
  float wrist_flex_rad = 0.0f; ///< Hand about its X (positive bends the palm side forward).
};

struct BodyPose {
  vec3 pelvis_m{0.0f};
  quat pelvis_rot{1, 0, 0, 0};
  /// Chest relative to the pelvis as yaw, pitch (positive bends forward), roll; spread over
  /// Spine, Spine1, Chest.
  vec3 spine_ypr_rad{0.0f};
  quat head_rot{1, 0, 0, 0};   ///< Clip-space head orientation; the neck takes 40% of the turn.
  std::array<vec2, 2> clavicle_rad{vec2(0.0f), vec2(0.0f)};  ///< Per side: (raise, protract).
  std::array<ArmPose, 2> arms;
  std::array<FootPose, 2> feet;
};

/// Component-wise blend (positions lerp, rotations slerp): w = 0 gives a, 1 gives b.
BodyPose mix(const BodyPose& a, const BodyPose& b, float w);

/// Chest frame and shoulder joints of a pose (forward kinematics of the torso only).
struct TorsoFrame {
  vec3 chest_m{0.0f};
  quat chest_rot{1, 0, 0, 0};
  std::array<vec3, 2> shoulder_m{vec3(0.0f), vec3(0.0f)};  ///< Arm joints (clip space).
  std::array<vec3, 2> hip_m{vec3(0.0f), vec3(0.0f)};       ///< UpLeg joints (clip space).
};
TorsoFrame torso_frame(const Skeleton& skeleton, const Rig& rig, const BodyPose& pose);

/// Spine joint rotation for a share of the chest's yaw/pitch/roll.
quat spine_joint_rot(vec3 spine_ypr_rad, float share);

/// Writes the skeleton's local translations (rest offsets; the pelvis position for joint 0) and
/// local rotations for the pose.
void solve_body_pose(const Skeleton& skeleton, const Rig& rig, const BodyPose& pose,
                     std::span<vec3> local_pos_m, std::span<quat> local_rot);

/// Bakes a clip at `fps`: frame f is solve_body_pose(pose_at(f / fps)), frames 0..num_frames-1.
/// Rotations are kept in one hemisphere from frame to frame so blending them stays short-arc.
Clip bake_clip(const Skeleton& skeleton, const Rig& rig, const std::string& name, int num_frames,
               float fps, const std::function<BodyPose(float)>& pose_at);

}  // namespace foresight::author

#pragma once
// A terrain actor's body at one frame, as the planners decide it, and how it drives the default
// skeleton (so terrain avatars are drawn like every other avatar).
//
// The paper's 22 degrees of freedom (its Fig. 1): the pelvis (position, heading: 4), each leg's
// hip flexion, knee and ankle in its sagittal plane (procedural_walk.hpp) and the hip's rotation
// about the vertical (the foot keeps the heading of the path where it stands while the pelvis
// turns along a curved path: the paper's second hip DOF), the waist's 2 and each arm's 4
// (upper_body.hpp): 18 angles besides the pelvis, which is also what a snapshot sends (schema
// TerrainBody, 56 bytes).
//
// On the default skeleton (anim/author/default_skeleton.cpp): Hips carries the position and the
// heading; Spine the waist (Spine1, Chest, Neck and Head stay at rest: the model's torso is rigid);
// LeftArm/RightArm the shoulder's flexion, abduction and twist, LeftForeArm/RightForeArm the elbow;
// LeftUpLeg/LeftLeg/LeftFoot (and the right ones) hip (rotation, then flexion), knee and ankle. The rotations are the
// model's own (upper_body.cpp, procedural_walk.cpp), so the skeleton's joints land where the
// planners checked them (terrain_body_test.cpp measures it).
#include "anim/pose.hpp"
#include "terrain/procedural_walk.hpp"
#include "terrain/upper_body.hpp"

#include <array>

namespace foresight::terrain {

struct TerrainBodyPose {
  vec3 pelvis_m{0.0f};      ///< The Hips joint, world.
  float heading_rad = 0.0f;
  std::array<LegPose, 2> legs{};  ///< [0] left, [1] right.
  std::array<float, 2> hip_yaw_rad{};  ///< Leg turned about the vertical from the pelvis' heading (+ toward +heading).
  UpperBodyConfig upper;
};

inline constexpr int kTerrainBodyAngles = 18;
/// The 18 angles in wire order: left hip flexion, hip yaw, knee, ankle, the same for the right leg,
/// waist flexion and rotation, left arm flexion, abduction, twist, elbow, then the right arm's.
std::array<float, kTerrainBodyAngles> terrain_body_angles(const TerrainBodyPose& body);
void terrain_body_set_angles(TerrainBodyPose& body, const std::array<float, kTerrainBodyAngles>& angles);

/// The body at `phase` of a planned step walked along `path` (legs by walk_step_sample; which leg
/// swings by `swing_left`; each hip turned to the path's heading at its ankle) with the upper body
/// `upper`.
TerrainBodyPose terrain_body_at(const WalkStep& step, const WalkParams& walk, const GroundPath& path, float phase,
                                bool swing_left, const UpperBodyConfig& upper);
/// Standing at `ground_m` (x, z) on ground at height ground_y_m, facing heading_rad: legs
/// straight, feet together, upper body in its pattern.
TerrainBodyPose terrain_body_standing(const WalkParams& walk, const UpperBodyParams& body, vec2 ground_m,
                                      float ground_y_m, float heading_rad);
/// The `t` (0..1) way from a to b, angles and position linearly, the heading along the shorter arc.
TerrainBodyPose terrain_body_lerp(const TerrainBodyPose& a, const TerrainBodyPose& b, float t);

/// The skeleton joints a terrain body drives.
struct TerrainSkeletonJoints {
  int hips = -1, spine = -1;
  std::array<int, 2> arm{-1, -1}, fore_arm{-1, -1}, up_leg{-1, -1}, leg{-1, -1}, foot{-1, -1};
};
/// Finds them by the default skeleton's names (Hips, Spine, LeftArm, ...). False if one is missing.
bool terrain_skeleton_joints(const Skeleton& skeleton, TerrainSkeletonJoints& out);

/// The body as a pose of `skeleton` (rest offsets; joint 0 the pelvis, world). `out` is resized
/// to the skeleton (no allocation when it already is).
void terrain_body_to_pose(const TerrainBodyPose& body, const Skeleton& skeleton, const TerrainSkeletonJoints& joints,
                          Pose& out);

}  // namespace foresight::terrain

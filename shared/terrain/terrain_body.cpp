#include "terrain/terrain_body.hpp"

#include <string>

namespace foresight::terrain {

namespace {

quat about_x(float a) { return glm::angleAxis(a, vec3(1.0f, 0.0f, 0.0f)); }
quat about_y(float a) { return glm::angleAxis(a, vec3(0.0f, 1.0f, 0.0f)); }
quat about_z(float a) { return glm::angleAxis(a, vec3(0.0f, 0.0f, 1.0f)); }
}  // namespace

std::array<float, kTerrainBodyAngles> terrain_body_angles(const TerrainBodyPose& b) {
  const UpperBodyConfig& u = b.upper;
  return {b.legs[0].hip_rad, b.hip_yaw_rad[0], b.legs[0].knee_rad, b.legs[0].ankle_rad,
          b.legs[1].hip_rad, b.hip_yaw_rad[1], b.legs[1].knee_rad, b.legs[1].ankle_rad,
          u.waist[0],        u.waist[1],
          u.arms[0][0],      u.arms[0][1],     u.arms[0][2],         u.arms[0][3],
          u.arms[1][0],      u.arms[1][1],     u.arms[1][2],         u.arms[1][3]};
}

void terrain_body_set_angles(TerrainBodyPose& b, const std::array<float, kTerrainBodyAngles>& a) {
  for (size_t leg = 0; leg < 2; ++leg) {
    b.legs[leg] = {a[leg * 4], a[leg * 4 + 2], a[leg * 4 + 3]};
    b.hip_yaw_rad[leg] = a[leg * 4 + 1];
  }
  b.upper.waist = {a[8], a[9], 0.0f, 0.0f};
  for (size_t arm = 0; arm < 2; ++arm)
    for (size_t i = 0; i < 4; ++i) b.upper.arms[arm][i] = a[10 + arm * 4 + i];
}

TerrainBodyPose terrain_body_at(const WalkStep& step, const WalkParams& walk, const GroundPath& path, float phase,
                                bool swing_left, const UpperBodyConfig& upper) {
  WalkFrame w;
  walk_step_sample(step, walk, phase, w);
  TerrainBodyPose b;
  b.pelvis_m = from_ground(ground_path_point(path, w.pelvis_m.x), w.pelvis_m.y);
  b.heading_rad = ground_path_heading(path, w.pelvis_m.x);
  const size_t swing = swing_left ? 0 : 1, stance = 1 - swing;
  b.legs[swing] = w.swing;
  b.legs[stance] = w.stance;
  b.hip_yaw_rad[swing] = wrap_angle(ground_path_heading(path, w.swing_ankle_m.x) - b.heading_rad);
  b.hip_yaw_rad[stance] = wrap_angle(ground_path_heading(path, w.stance_ankle_m.x) - b.heading_rad);
  b.upper = upper;
  return b;
}

TerrainBodyPose terrain_body_standing(const WalkParams& walk, const UpperBodyParams& body, vec2 ground_m,
                                      float ground_y_m, float heading_rad) {
  TerrainBodyPose b;
  b.pelvis_m = from_ground(ground_m, ground_y_m + walk.ankle_height_m + walk.thigh_m + walk.shin_m +
                                         walk.hip_below_pelvis_m);
  b.heading_rad = heading_rad;
  const PelvisFrame still{b.pelvis_m, heading_rad, 0.0f, 0.0f};
  b.upper.arms[0] = upper_body_pattern(body, BodyPart::kLeftArm, still);
  b.upper.arms[1] = upper_body_pattern(body, BodyPart::kRightArm, still);
  return b;
}

TerrainBodyPose terrain_body_lerp(const TerrainBodyPose& a, const TerrainBodyPose& b, float t) {
  TerrainBodyPose out;
  out.pelvis_m = glm::mix(a.pelvis_m, b.pelvis_m, t);
  out.heading_rad = wrap_angle(a.heading_rad + wrap_angle(b.heading_rad - a.heading_rad) * t);
  const auto x = terrain_body_angles(a), y = terrain_body_angles(b);
  std::array<float, kTerrainBodyAngles> mixed;
  for (size_t i = 0; i < mixed.size(); ++i) mixed[i] = x[i] + (y[i] - x[i]) * t;
  terrain_body_set_angles(out, mixed);
  return out;
}

bool terrain_skeleton_joints(const Skeleton& s, TerrainSkeletonJoints& out) {
  out.hips = s.find_joint("Hips");
  out.spine = s.find_joint("Spine");
  bool ok = out.hips >= 0 && out.spine >= 0;
  for (size_t side = 0; side < 2; ++side) {
    const std::string p = side == 0 ? "Left" : "Right";
    out.arm[side] = s.find_joint(p + "Arm");
    out.fore_arm[side] = s.find_joint(p + "ForeArm");
    out.up_leg[side] = s.find_joint(p + "UpLeg");
    out.leg[side] = s.find_joint(p + "Leg");
    out.foot[side] = s.find_joint(p + "Foot");
    ok = ok && out.arm[side] >= 0 && out.fore_arm[side] >= 0 && out.up_leg[side] >= 0 && out.leg[side] >= 0 &&
         out.foot[side] >= 0;
  }
  return ok;
}

void terrain_body_to_pose(const TerrainBodyPose& b, const Skeleton& s, const TerrainSkeletonJoints& j, Pose& out) {
  out.resize(s.num_joints());
  for (int i = 0; i < s.num_joints(); ++i) {
    out.local_pos_m[static_cast<size_t>(i)] = s.rest_offsets_m[static_cast<size_t>(i)];
    out.local_rot[static_cast<size_t>(i)] = quat(1.0f, 0.0f, 0.0f, 0.0f);
  }
  auto rot = [&out](int joint) -> quat& { return out.local_rot[static_cast<size_t>(joint)]; };
  out.local_pos_m[static_cast<size_t>(j.hips)] = b.pelvis_m;
  rot(j.hips) = quat_from_heading(b.heading_rad);
  // The same rotations as upper_body.cpp's waist_frame and arm_points (rot_x, rot_y, rot_z).
  rot(j.spine) = about_x(b.upper.waist[0]) * about_y(b.upper.waist[1]);
  for (size_t side = 0; side < 2; ++side) {
    const float sign = side == 0 ? 1.0f : -1.0f;
    const PartConfig& q = b.upper.arms[side];
    rot(j.arm[side]) = about_z(sign * q[1]) * about_x(-q[0]) * about_y(sign * q[2]);
    rot(j.fore_arm[side]) = about_x(-q[3]);
    // Sagittal legs (procedural_walk.cpp): the thigh hip_rad forward of straight down, the shin
    // knee_rad back from the thigh, the foot ankle_rad toes-up from square to the shin.
    const LegPose& leg = b.legs[side];
    rot(j.up_leg[side]) = about_y(b.hip_yaw_rad[side]) * about_x(-leg.hip_rad);
    rot(j.leg[side]) = about_x(leg.knee_rad);
    rot(j.foot[side]) = about_x(-leg.ankle_rad);
  }
}

}  // namespace foresight::terrain

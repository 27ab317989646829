#include "fighter/pose_cloud.hpp"

#include <cassert>

namespace foresight {

std::array<int, kPoseKeyPoints> fighter_key_joints(const FighterRig& rig) {
  assert(!rig.spine.empty());
  std::array<int, kPoseKeyPoints> j{};
  j[0] = rig.pelvis;
  j[1] = rig.spine.back();  // The chest: the neck's parent.
  j[2] = rig.head;
  for (int side = 0; side < 2; ++side) {
    const FighterLimb& arm = rig.arm[static_cast<std::size_t>(side)];
    const FighterLimb& leg = rig.leg[static_cast<std::size_t>(side)];
    const std::size_t base = 3 + static_cast<std::size_t>(side) * 6;
    j[base + 0] = arm.root;
    j[base + 1] = arm.mid;
    j[base + 2] = arm.end;
    j[base + 3] = leg.root;
    j[base + 4] = leg.mid;
    j[base + 5] = leg.end;
  }
  return j;
}

void fighter_key_points_m(const FighterRig& rig, std::span<const vec3> global_pos_m, const Placement& root,
                          std::span<vec3, kPoseKeyPoints> out) {
  const Placement to_root = root.inverse();
  const std::array<int, kPoseKeyPoints> joints = fighter_key_joints(rig);
  for (int i = 0; i < kPoseKeyPoints; ++i)
    out[static_cast<std::size_t>(i)] = to_root.apply(global_pos_m[static_cast<std::size_t>(joints[static_cast<std::size_t>(i)])]);
}

void pose_cloud_pack(std::span<const vec3, kPoseKeyPoints> points, float* pts, float& sum_sq_xz, vec2& centroid_xz) {
  vec2 c(0.0f);
  for (const vec3& p : points) c += vec2(p.x, p.z);
  c /= static_cast<float>(kPoseKeyPoints);
  float ss = 0.0f;
  for (int i = 0; i < kPoseKeyPoints; ++i) {
    const vec3& p = points[static_cast<std::size_t>(i)];
    const float x = p.x - c.x, z = p.z - c.y;
    pts[i] = x;
    pts[kPoseKeyPoints + i] = p.y;
    pts[2 * kPoseKeyPoints + i] = z;
    ss += x * x + z * z;
  }
  sum_sq_xz = ss;
  centroid_xz = c;
}

void pose_cloud_from_points(std::span<const vec3, kPoseKeyPoints> points, PoseCloud& out) {
  pose_cloud_pack(points, out.pts.data(), out.sum_sq_xz, out.centroid_xz);
}

Placement pose_cloud_alignment(float c, float s, vec2 a_centroid_xz, vec2 b_centroid_xz) {
  const float r = std::sqrt(c * c + s * s);
  // A degenerate cloud (all points on the Y axis) has no preferred heading: keep it.
  const float cos_h = r > 1e-12f ? c / r : 1.0f;
  const float sin_h = r > 1e-12f ? s / r : 0.0f;
  Placement p;
  p.heading_rad = std::atan2(sin_h, cos_h);
  p.pos_m = a_centroid_xz - rotate_ground(b_centroid_xz, p.heading_rad);
  return p;
}

float pose_points_distance_sq(std::span<const vec3, kPoseKeyPoints> a, std::span<const vec3, kPoseKeyPoints> b,
                              Placement* b_to_a) {
  PoseCloud ca, cb;
  pose_cloud_from_points(a, ca);
  pose_cloud_from_points(b, cb);
  float c = 0.0f, s = 0.0f;
  const float d = pose_cloud_distance_sq(ca.pts.data(), ca.sum_sq_xz, cb.pts.data(), cb.sum_sq_xz, c, s);
  if (b_to_a != nullptr) *b_to_a = pose_cloud_alignment(c, s, ca.centroid_xz, cb.centroid_xz);
  return d;
}

}  // namespace foresight

#include "terrain/upper_body.hpp"

#include <algorithm>
#include <cmath>

namespace foresight::terrain {

namespace {

// Rotations as column-major glm matrices (see the header for the axes).
glm::mat3 rot_x(float a) {
  const float c = std::cos(a), s = std::sin(a);
  return glm::mat3(vec3(1, 0, 0), vec3(0, c, s), vec3(0, -s, c));
}
glm::mat3 rot_y(float a) {
  const float c = std::cos(a), s = std::sin(a);
  return glm::mat3(vec3(c, 0, -s), vec3(0, 1, 0), vec3(s, 0, c));
}
glm::mat3 rot_z(float a) {
  const float c = std::cos(a), s = std::sin(a);
  return glm::mat3(vec3(c, s, 0), vec3(-s, c, 0), vec3(0, 0, 1));
}

struct WaistFrame {
  vec3 pivot_m;
  glm::mat3 rot;  ///< Torso axes in the world.
};

WaistFrame waist_frame(const UpperBodyParams& p, const PelvisFrame& f, const PartConfig& waist) {
  return {f.pos_m + vec3(0, p.waist_above_pelvis_m, 0), rot_y(f.heading_rad) * rot_x(waist[0]) * rot_y(waist[1])};
}

/// Spheres at most one radius apart along a capsule's axis (upper_body_params_valid keeps the
/// total within BodySpheres::kCapacity).
int capsule_spheres(float length_m, float radius_m) {
  return std::max(static_cast<int>(std::ceil(length_m / radius_m)) + 1, 2);
}

void add_capsule(BodySpheres& out, vec3 a, vec3 b, float radius) {
  const float len = glm::length(b - a);
  const int n = std::min(capsule_spheres(len, radius), BodySpheres::kCapacity - out.count);
  for (int i = 0; i < n; ++i) {
    const vec3 c = a + (b - a) * (static_cast<float>(i) / static_cast<float>(n - 1));
    out.spheres[static_cast<size_t>(out.count++)] = glm::vec4(c, radius);
  }
}

}  // namespace

const char* body_part_name(BodyPart part) {
  switch (part) {
    case BodyPart::kWaist: return "waist";
    case BodyPart::kLeftArm: return "left arm";
    case BodyPart::kRightArm: return "right arm";
  }
  return "?";
}

bool upper_body_params_valid(const UpperBodyParams& p) {
  const float radii[] = {p.torso_radius_m, p.head_radius_m, p.upper_arm_radius_m, p.forearm_radius_m};
  const float lengths[] = {p.neck_above_waist_m, p.upper_arm_m, p.forearm_m, p.shoulder_half_width_m,
                           p.head_centre_above_waist_m, p.shoulder_above_waist_m, p.waist_above_pelvis_m};
  for (float r : radii)
    if (!(r > 0.0f && r < 1.0f)) return false;
  for (float l : lengths)
    if (!(l >= 0.0f && l < 2.0f)) return false;
  if (!(p.margin_m >= 0.0f && p.margin_m < 0.1f) || !std::isfinite(p.head_forward_m)) return false;
  const int torso = capsule_spheres(p.neck_above_waist_m, p.torso_radius_m + p.margin_m) + 3;  // + head, shoulders
  const int arm = capsule_spheres(p.upper_arm_m, p.upper_arm_radius_m + p.margin_m) +
                  capsule_spheres(p.forearm_m, p.forearm_radius_m + p.margin_m);
  return torso <= BodySpheres::kCapacity && arm <= BodySpheres::kCapacity;
}

PartConfig upper_body_pattern(const UpperBodyParams& p, BodyPart part, const PelvisFrame& f) {
  if (part == BodyPart::kWaist) return PartConfig{};
  const float hip = part == BodyPart::kLeftArm ? f.left_hip_rad : f.right_hip_rad;
  return clamp_to_limits(p, part, PartConfig{-p.arm_swing_gain * hip, p.arm_rest_abduction_rad, 0.0f,
                                             p.arm_rest_elbow_rad});
}

PartConfig clamp_to_limits(const UpperBodyParams& p, BodyPart part, const PartConfig& q) {
  const bool waist = part == BodyPart::kWaist;
  const PartConfig& lo = waist ? p.waist_min : p.arm_min;
  const PartConfig& hi = waist ? p.waist_max : p.arm_max;
  PartConfig out{};
  for (int i = 0; i < part_dof(part); ++i) out[static_cast<size_t>(i)] = std::clamp(q[i], lo[i], hi[i]);
  return out;
}

void waist_spheres(const UpperBodyParams& p, const PelvisFrame& f, const PartConfig& waist, BodySpheres& out) {
  out.count = 0;
  const WaistFrame w = waist_frame(p, f, waist);
  add_capsule(out, w.pivot_m, w.pivot_m + w.rot * vec3(0, p.neck_above_waist_m, 0), p.torso_radius_m + p.margin_m);
  out.spheres[static_cast<size_t>(out.count++)] =
      glm::vec4(w.pivot_m + w.rot * vec3(0, p.head_centre_above_waist_m, p.head_forward_m), p.head_radius_m + p.margin_m);
  // The shoulder joints ride on the torso: no arm motion moves them, so the waist keeps them clear
  // (turning the chest away from a shelf beside it, as in the paper's Fig. 9b).
  for (float side : {1.0f, -1.0f})
    out.spheres[static_cast<size_t>(out.count++)] = glm::vec4(
        w.pivot_m + w.rot * vec3(side * p.shoulder_half_width_m, p.shoulder_above_waist_m, 0),
        p.upper_arm_radius_m + p.margin_m);
}

ArmPoints arm_points(const UpperBodyParams& p, const PelvisFrame& f, const PartConfig& waist, BodyPart arm,
                     const PartConfig& q) {
  const WaistFrame w = waist_frame(p, f, waist);
  const float side = arm == BodyPart::kLeftArm ? 1.0f : -1.0f;
  const glm::mat3 upper = w.rot * rot_z(side * q[1]) * rot_x(-q[0]) * rot_y(side * q[2]);
  ArmPoints out;
  out.shoulder_m = w.pivot_m + w.rot * vec3(side * p.shoulder_half_width_m, p.shoulder_above_waist_m, 0);
  out.elbow_m = out.shoulder_m + upper * vec3(0, -p.upper_arm_m, 0);
  out.hand_m = out.elbow_m + upper * (rot_x(-q[3]) * vec3(0, -p.forearm_m, 0));
  return out;
}

void arm_spheres(const UpperBodyParams& p, const PelvisFrame& f, const PartConfig& waist, BodyPart arm,
                 const PartConfig& q, BodySpheres& out) {
  out.count = 0;
  const ArmPoints a = arm_points(p, f, waist, arm, q);
  add_capsule(out, a.shoulder_m, a.elbow_m, p.upper_arm_radius_m + p.margin_m);
  add_capsule(out, a.elbow_m, a.hand_m, p.forearm_radius_m + p.margin_m);
}

vec3 head_top(const UpperBodyParams& p, const PelvisFrame& f, const PartConfig& waist) {
  const WaistFrame w = waist_frame(p, f, waist);
  return w.pivot_m + w.rot * vec3(0, p.head_centre_above_waist_m + p.head_radius_m, p.head_forward_m);
}

void gather_upper_body_obstacles(const Scene& scene, std::span<const PelvisFrame> track, float reach_m,
                                 float min_top_m, UpperBodyObstacles& out) {
  out.count = 0;
  out.overflow = false;
  if (track.empty()) return;
  vec2 lo(track[0].pos_m.x, track[0].pos_m.z), hi = lo;
  for (const PelvisFrame& f : track) {
    lo = glm::min(lo, vec2(f.pos_m.x, f.pos_m.z));
    hi = glm::max(hi, vec2(f.pos_m.x, f.pos_m.z));
  }
  lo -= vec2(reach_m);
  hi += vec2(reach_m);
  for (const SceneBox& b : scene.boxes) {
    if (b.max_m.y <= min_top_m || b.max_m.x < lo.x || b.min_m.x > hi.x || b.max_m.z < lo.y || b.min_m.z > hi.y)
      continue;
    if (out.count == UpperBodyObstacles::kCapacity) {
      out.overflow = true;
      return;
    }
    out.min_m[static_cast<size_t>(out.count)] = b.min_m;
    out.max_m[static_cast<size_t>(out.count)] = b.max_m;
    ++out.count;
  }
}

bool spheres_clear(const BodySpheres& spheres, const UpperBodyObstacles& obstacles) {
  for (int b = 0; b < obstacles.count; ++b) {
    const vec3 lo = obstacles.min_m[static_cast<size_t>(b)], hi = obstacles.max_m[static_cast<size_t>(b)];
    for (int i = 0; i < spheres.count; ++i) {
      const glm::vec4 s = spheres.spheres[static_cast<size_t>(i)];
      const vec3 c(s);
      const vec3 d = glm::max(glm::max(lo - c, c - hi), vec3(0.0f));
      if (glm::dot(d, d) < s.w * s.w) return false;
    }
  }
  return true;
}

bool upper_body_clear(const UpperBodyParams& params, const PelvisFrame& frame, const UpperBodyConfig& config,
                      const UpperBodyObstacles& obstacles) {
  BodySpheres s;
  waist_spheres(params, frame, config.waist, s);
  if (!spheres_clear(s, obstacles)) return false;
  for (BodyPart arm : {BodyPart::kLeftArm, BodyPart::kRightArm}) {
    arm_spheres(params, frame, config.waist, arm, config.part(arm), s);
    if (!spheres_clear(s, obstacles)) return false;
  }
  return true;
}

}  // namespace foresight::terrain

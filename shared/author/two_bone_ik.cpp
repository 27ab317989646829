#include "author/two_bone_ik.hpp"

#include <algorithm>
#include <cmath>

namespace foresight::author {
namespace {

// Unit vector perpendicular to `axis` (unit) closest to `v`; `fallback` when v is parallel.
vec3 perpendicular_part(vec3 v, vec3 axis, vec3 fallback) {
  vec3 p = v - axis * glm::dot(v, axis);
  if (glm::length(p) < 1e-5f) p = fallback - axis * glm::dot(fallback, axis);
  if (glm::length(p) < 1e-5f) p = glm::cross(axis, std::abs(axis.x) < 0.9f ? vec3(1, 0, 0) : vec3(0, 0, 1));
  return glm::normalize(p);
}

// Exponential approach instead of a hard clamp: a straightening limb slows down as it nears full
// extension rather than snapping straight (the classic IK "pop").
float soft_reach(float d, float full) {
  const float start = kIkSoftReachStart * full;
  if (d <= start) return d;
  const float room = full * 0.9999f - start;
  return start + room * (1.0f - std::exp(-(d - start) / room));
}

}  // namespace

TwoBoneSolution solve_two_bone(vec3 root_m, vec3 target_m, float upper_m, float lower_m,
                               vec3 bend_dir, HingeSide hinge) {
  TwoBoneSolution out;
  vec3 to_target = target_m - root_m;
  float d = glm::length(to_target);
  const vec3 dir = d > 1e-6f ? to_target / d : vec3(0, -1, 0);
  const float full = upper_m + lower_m;
  const float d_min = std::abs(upper_m - lower_m) + 1e-4f;
  const float d_eff = std::max(soft_reach(d, full), d_min);
  out.reached = std::abs(d_eff - d) < 1e-5f;

  // Law of cosines: the angle at the root between root->end and the upper bone.
  const float cos_root =
      std::clamp((upper_m * upper_m + d_eff * d_eff - lower_m * lower_m) / (2 * upper_m * d_eff),
                 -1.0f, 1.0f);
  const float sin_root = std::sqrt(std::max(0.0f, 1.0f - cos_root * cos_root));
  const vec3 bend = perpendicular_part(bend_dir, dir, vec3(0, 0, 1));
  out.end_m = root_m + dir * d_eff;
  out.mid_m = root_m + (dir * cos_root + bend * sin_root) * upper_m;

  // Upper bone frame: -Y along the bone, Z in the limb plane (towards the bend for a knee, away
  // from it for an elbow, matching each hinge's natural folding side), X the hinge axis.
  const vec3 y_axis = glm::normalize(root_m - out.mid_m);
  const float side = hinge == HingeSide::kKnee ? 1.0f : -1.0f;
  const vec3 z_axis = perpendicular_part(bend * side, y_axis, dir * -side);
  const vec3 x_axis = glm::cross(y_axis, z_axis);
  out.upper_global = glm::normalize(glm::quat_cast(glm::mat3(x_axis, y_axis, z_axis)));

  // Lower hinge: the angle about X that takes the rest direction (-Y) to mid->end.
  const vec3 lower_dir = glm::inverse(out.upper_global) * glm::normalize(out.end_m - out.mid_m);
  const float angle = std::atan2(-lower_dir.z, -lower_dir.y);
  out.lower_local = glm::angleAxis(angle, vec3(1, 0, 0));
  return out;
}

}  // namespace foresight::author

#pragma once
// Math vocabulary of Foresight: GLM types, Y up, metres, radians.
//
// Ground plane: a 2D point (x, z) is stored in glm::vec2 as {x, y} = {world x, world z}.
// Heading: rotation about +Y; heading 0 faces +Z, the character's left is +X.
//   forward(heading) = (sin h, 0, cos h).
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cmath>
#include <numbers>

namespace foresight {

using glm::quat;
using glm::vec2;
using glm::vec3;

inline constexpr float kPi = std::numbers::pi_v<float>;
inline constexpr float kTwoPi = 2.0f * kPi;

inline float radians(float degrees) { return degrees * (kPi / 180.0f); }
inline float degrees(float radians) { return radians * (180.0f / kPi); }

/// Wraps an angle to (-pi, pi].
inline float wrap_angle(float a_rad) {
  a_rad = std::remainder(a_rad, kTwoPi);
  return a_rad <= -kPi ? a_rad + kTwoPi : a_rad;
}

/// Rotates a ground-plane vector by heading (about +Y, same sense as quat_from_heading).
inline vec2 rotate_ground(vec2 v, float heading_rad) {
  const float c = std::cos(heading_rad), s = std::sin(heading_rad);
  return {c * v.x + s * v.y, -s * v.x + c * v.y};
}

inline vec2 ground(vec3 p) { return {p.x, p.z}; }

/// The offset of `p` from the line through `a` and `b` (the part of p - a square to b - a); zero
/// when a and b coincide. A knee's side: offset_from_line(knee, hip, ankle).
inline vec3 offset_from_line(vec3 p, vec3 a, vec3 b) {
  const vec3 axis = b - a;
  const float len2 = glm::dot(axis, axis);
  return len2 > 0.0f ? (p - a) - axis * (glm::dot(p - a, axis) / len2) : vec3(0.0f);
}
inline vec3 from_ground(vec2 g, float y) { return {g.x, y, g.y}; }

inline quat quat_from_heading(float heading_rad) {
  return glm::angleAxis(heading_rad, vec3(0.0f, 1.0f, 0.0f));
}

/// Heading of a horizontal direction (ignores y). Forward +Z is 0.
inline float heading_of(vec3 dir) { return std::atan2(dir.x, dir.z); }
inline float heading_of(vec2 ground_dir) { return std::atan2(ground_dir.x, ground_dir.y); }

/// A rigid transform of the ground plane: where an avatar stands and which way it faces.
/// apply(p) = rotate_ground(p, heading_rad) + pos_m.
struct Placement {
  vec2 pos_m{0.0f};
  float heading_rad = 0.0f;

  vec2 apply(vec2 p) const { return rotate_ground(p, heading_rad) + pos_m; }
  vec3 apply(vec3 p) const { return from_ground(apply(ground(p)), p.y); }
  quat apply(quat q) const { return quat_from_heading(heading_rad) * q; }

  /// this ∘ b: first b, then this.
  Placement compose(const Placement& b) const {
    return {apply(b.pos_m), wrap_angle(heading_rad + b.heading_rad)};
  }
  Placement inverse() const {
    return {rotate_ground(-pos_m, -heading_rad), wrap_angle(-heading_rad)};
  }
};

}  // namespace foresight

#pragma once
// Scalar shaping functions for procedural animation: eases, ramps, a smooth minimum, cubic
// Hermite, angle interpolation. All are pure and deterministic.
#include "math/types.hpp"

#include <algorithm>
#include <cmath>

namespace foresight::author {

inline float clamp01(float x) { return std::clamp(x, 0.0f, 1.0f); }
inline float lerp(float a, float b, float w) { return a + (b - a) * w; }
inline vec3 lerp(vec3 a, vec3 b, float w) { return a + (b - a) * w; }
inline vec2 lerp(vec2 a, vec2 b, float w) { return a + (b - a) * w; }

/// 3x^2 - 2x^3 on [0, 1]: zero slope at both ends.
inline float smoothstep01(float x) {
  x = clamp01(x);
  return x * x * (3.0f - 2.0f * x);
}
/// 6x^5 - 15x^4 + 10x^3 on [0, 1]: zero slope and curvature at both ends.
inline float smootherstep01(float x) {
  x = clamp01(x);
  return x * x * x * (x * (6.0f * x - 15.0f) + 10.0f);
}
/// smoothstep01 of where x lies in [a, b].
inline float ramp(float x, float a, float b) { return smoothstep01((x - a) / (b - a)); }

/// Polynomial smooth minimum: equals min(a, b) when they differ by more than k, and blends
/// (never above the min) within k.
inline float soft_min(float a, float b, float k) {
  const float h = std::max(k - std::abs(a - b), 0.0f) / k;
  return std::min(a, b) - h * h * k * 0.25f;
}

/// Cubic Hermite between p0 and p1 with end tangents m0, m1 (per unit s), s in [0, 1].
template <class T>
T hermite(T p0, T m0, T p1, T m1, float s) {
  const float s2 = s * s, s3 = s2 * s;
  return p0 * (2 * s3 - 3 * s2 + 1) + m0 * (s3 - 2 * s2 + s) + p1 * (-2 * s3 + 3 * s2) +
         m1 * (s3 - s2);
}
/// Interpolates angles along the shorter arc.
inline float lerp_angle(float a_rad, float b_rad, float w) {
  return a_rad + wrap_angle(b_rad - a_rad) * w;
}

/// Unit quaternion from yaw (about +Y), then pitch (about +X, positive tips +Y towards +Z), then
/// roll (about +Z, positive lifts +X): q = Y(yaw) * X(pitch) * Z(roll).
inline quat quat_ypr(float yaw_rad, float pitch_rad, float roll_rad) {
  return glm::angleAxis(yaw_rad, vec3(0, 1, 0)) * glm::angleAxis(pitch_rad, vec3(1, 0, 0)) *
         glm::angleAxis(roll_rad, vec3(0, 0, 1));
}

/// Forward (+Z rotated by heading) on the ground plane, as a 3D vector.
inline vec3 forward3(float heading_rad) {
  return vec3(std::sin(heading_rad), 0.0f, std::cos(heading_rad));
}
/// The character's left (+X rotated by heading), as a 3D vector.
inline vec3 left3(float heading_rad) {
  return vec3(std::cos(heading_rad), 0.0f, -std::sin(heading_rad));
}

}  // namespace foresight::author

#include "world/body_volume.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace foresight {

BodyVolume body_volume_from_pose(std::span<const vec3> joint_pos_m, vec2 facing, float margin_m,
                                 float head_top_m) {
  if (joint_pos_m.empty()) return {};
  const float len = glm::length(facing);
  const vec2 axis = len > 1e-6f ? facing / len : vec2(0.0f, 1.0f);
  const vec2 side(-axis.y, axis.x);
  float v_lo = std::numeric_limits<float>::max(), v_hi = -v_lo;
  float y_lo = joint_pos_m[0].y, y_hi = y_lo;
  for (const vec3& p : joint_pos_m) {
    const float v = glm::dot(ground(p), side);
    v_lo = std::min(v_lo, v);
    v_hi = std::max(v_hi, v);
    y_lo = std::min(y_lo, p.y);
    y_hi = std::max(y_hi, p.y);
  }
  const float radius = 0.5f * (v_hi - v_lo), mid_v = 0.5f * (v_hi + v_lo);
  // A joint is held when the core segment reaches within sqrt(R^2 - dv^2) of it along the axis:
  // the core must span [max(u - s), min(u + s)]; if that is empty, one point does.
  float a = std::numeric_limits<float>::max(), b = -a;
  for (const vec3& p : joint_pos_m) {
    const float dv = glm::dot(ground(p), side) - mid_v, u = glm::dot(ground(p), axis);
    const float s = std::sqrt(std::max(radius * radius - dv * dv, 0.0f));
    a = std::min(a, u + s);
    b = std::max(b, u - s);
  }
  if (a > b) a = b = 0.5f * (a + b);
  BodyVolume v;
  v.center_m = side * mid_v + axis * (0.5f * (a + b));
  v.half_axis_m = axis * (0.5f * (b - a));
  v.radius_m = radius + margin_m;
  v.y_min_m = y_lo;
  v.y_max_m = y_hi + head_top_m;
  return v;
}

float segment_distance_sq(vec2 p0, vec2 p1, vec2 q0, vec2 q1) {
  // Closest points of two segments (Ericson, Real-Time Collision Detection, 5.1.9).
  const vec2 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const float a = glm::dot(d1, d1), e = glm::dot(d2, d2), f = glm::dot(d2, r);
  constexpr float kEps = 1e-12f;
  float s = 0.0f, t = 0.0f;
  if (a <= kEps && e <= kEps) {
    // both points
  } else if (a <= kEps) {
    t = std::clamp(f / e, 0.0f, 1.0f);
  } else {
    const float c = glm::dot(d1, r);
    if (e <= kEps) {
      s = std::clamp(-c / a, 0.0f, 1.0f);
    } else {
      const float b = glm::dot(d1, d2), denom = a * e - b * b;
      s = denom > kEps ? std::clamp((b * f - c * e) / denom, 0.0f, 1.0f) : 0.0f;
      t = (b * s + f) / e;
      if (t < 0.0f) {
        t = 0.0f;
        s = std::clamp(-c / a, 0.0f, 1.0f);
      } else if (t > 1.0f) {
        t = 1.0f;
        s = std::clamp((b - c) / a, 0.0f, 1.0f);
      }
    }
  }
  const vec2 gap = (p0 + d1 * s) - (q0 + d2 * t);
  return glm::dot(gap, gap);
}

bool any_footprints_overlap(std::span<BodyVolume> bodies) {
  float widest = 0.0f;
  for (const BodyVolume& b : bodies) widest = std::max(widest, b.reach_m());
  std::sort(bodies.begin(), bodies.end(), [](const BodyVolume& a, const BodyVolume& b) { return a.center_m.x < b.center_m.x; });
  for (size_t i = 0; i < bodies.size(); ++i) {
    const BodyVolume& a = bodies[i];
    const float reach_a = a.reach_m(), reach = reach_a + widest;
    for (size_t j = i + 1; j < bodies.size() && bodies[j].center_m.x - a.center_m.x < reach; ++j) {
      // Each footprint lies in the disc of its reach: discs apart (with a rounding slack), no
      // overlap, and no segment distance to compute (most pairs in the x sweep are metres apart in z).
      const vec2 d = bodies[j].center_m - a.center_m;
      const float r = reach_a + bodies[j].reach_m() + 1e-3f;
      if (glm::dot(d, d) < r * r && footprints_overlap(a, bodies[j])) return true;
    }
  }
  return false;
}

}  // namespace foresight

#include "world/body_volume.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <vector>

namespace foresight {
namespace {

constexpr int kAxesTried = 36;  // every 5 degrees over half a turn

/// A disc the capsule must hold: centre and radius (0 for a joint).
struct Disc {
  vec2 c;
  float r;
};

/// The narrowest capsule along `axis` holding every disc, grown by `margin_m`.
BodyVolume capsule_along(std::span<const Disc> discs, vec2 axis, float margin_m) {
  const vec2 side(-axis.y, axis.x);
  float v_lo = std::numeric_limits<float>::max(), v_hi = -v_lo;
  for (const Disc& d : discs) {
    const float v = glm::dot(d.c, side);
    v_lo = std::min(v_lo, v - d.r);
    v_hi = std::max(v_hi, v + d.r);
  }
  const float radius = 0.5f * (v_hi - v_lo), mid_v = 0.5f * (v_hi + v_lo);
  // Each disc is held when the core segment reaches within sqrt((R - r)^2 - dv^2) of it along
  // the axis: the segment must span [max(u - s), min(u + s)]; if that is empty, one point does.
  float a = std::numeric_limits<float>::max(), b = -a;
  for (const Disc& d : discs) {
    const float dv = glm::dot(d.c, side) - mid_v, u = glm::dot(d.c, axis);
    const float s = std::sqrt(std::max((radius - d.r) * (radius - d.r) - dv * dv, 0.0f));
    a = std::min(a, u + s);
    b = std::max(b, u - s);
  }
  if (a > b) a = b = 0.5f * (a + b);
  BodyVolume v;
  v.center_m = side * mid_v + axis * (0.5f * (a + b));
  v.half_axis_m = axis * (0.5f * (b - a));
  v.radius_m = radius + margin_m;
  return v;
}

/// Narrowest first (what decides whether a body passes a gap), then shortest.
BodyVolume narrowest_capsule(std::span<const Disc> discs, float margin_m) {
  BodyVolume best;
  float best_radius = std::numeric_limits<float>::max(), best_length = best_radius;
  for (int i = 0; i < kAxesTried; ++i) {
    const float angle = kPi * static_cast<float>(i) / kAxesTried;
    const BodyVolume v = capsule_along(discs, vec2(std::cos(angle), std::sin(angle)), margin_m);
    const float length = glm::length(v.half_axis_m);
    if (v.radius_m < best_radius - 1e-4f || (v.radius_m <= best_radius + 1e-4f && length < best_length))
      best = v, best_radius = v.radius_m, best_length = length;
  }
  return best;
}

}  // namespace

BodyVolume body_volume_from_pose(std::span<const vec3> joint_pos_m, float margin_m,
                                 float head_top_m) {
  if (joint_pos_m.empty()) return {};
  std::vector<Disc> discs;
  discs.reserve(joint_pos_m.size());
  float y_lo = joint_pos_m[0].y, y_hi = y_lo;
  for (const vec3& p : joint_pos_m) {
    discs.push_back({ground(p), 0.0f});
    y_lo = std::min(y_lo, p.y);
    y_hi = std::max(y_hi, p.y);
  }
  BodyVolume v = narrowest_capsule(discs, margin_m);
  v.y_min_m = y_lo;
  v.y_max_m = y_hi + head_top_m;
  return v;
}

BodyVolume enclosing_volume(const BodyVolume& a, const BodyVolume& b) {
  const std::array<Disc, 4> ends{Disc{a.center_m - a.half_axis_m, a.radius_m}, Disc{a.center_m + a.half_axis_m, a.radius_m},
                                 Disc{b.center_m - b.half_axis_m, b.radius_m}, Disc{b.center_m + b.half_axis_m, b.radius_m}};
  BodyVolume out = narrowest_capsule(ends, 0.0f);
  out.y_min_m = std::min(a.y_min_m, b.y_min_m);
  out.y_max_m = std::max(a.y_max_m, b.y_max_m);
  return out;
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
    const float reach = a.reach_m() + widest;
    for (size_t j = i + 1; j < bodies.size() && bodies[j].center_m.x - a.center_m.x < reach; ++j)
      if (footprints_overlap(a, bodies[j])) return true;
  }
  return false;
}

}  // namespace foresight

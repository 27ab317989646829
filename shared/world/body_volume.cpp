#include "world/body_volume.hpp"

#include <algorithm>

namespace foresight {

BodyVolume body_volume_from_pose(std::span<const vec3> joint_pos_m, float margin_m,
                                 float head_top_m) {
  BodyVolume v;
  if (joint_pos_m.empty()) return v;
  // Centre of the ground-plane bounding box; the disc covers every joint from there.
  vec2 lo = ground(joint_pos_m[0]), hi = lo;
  float y_lo = joint_pos_m[0].y, y_hi = y_lo;
  for (const vec3& p : joint_pos_m) {
    lo = glm::min(lo, ground(p));
    hi = glm::max(hi, ground(p));
    y_lo = std::min(y_lo, p.y);
    y_hi = std::max(y_hi, p.y);
  }
  v.center_m = 0.5f * (lo + hi);
  float r2 = 0.0f;
  for (const vec3& p : joint_pos_m) {
    const vec2 d = ground(p) - v.center_m;
    r2 = std::max(r2, glm::dot(d, d));
  }
  v.radius_m = std::sqrt(r2) + margin_m;
  v.y_min_m = y_lo;
  v.y_max_m = y_hi + head_top_m;
  return v;
}

BodyVolume enclosing_volume(const BodyVolume& a, const BodyVolume& b) {
  BodyVolume out;
  out.y_min_m = std::min(a.y_min_m, b.y_min_m);
  out.y_max_m = std::max(a.y_max_m, b.y_max_m);
  const float d = glm::length(b.center_m - a.center_m);
  if (d + b.radius_m <= a.radius_m) {  // b inside a
    out.center_m = a.center_m, out.radius_m = a.radius_m;
  } else if (d + a.radius_m <= b.radius_m) {  // a inside b
    out.center_m = b.center_m, out.radius_m = b.radius_m;
  } else {
    out.radius_m = 0.5f * (d + a.radius_m + b.radius_m);
    out.center_m = a.center_m + (b.center_m - a.center_m) * ((out.radius_m - a.radius_m) / d);
  }
  return out;
}

bool any_discs_overlap(std::span<BodyVolume> bodies) {
  float widest = 0.0f;
  for (const BodyVolume& b : bodies) widest = std::max(widest, b.radius_m);
  std::sort(bodies.begin(), bodies.end(), [](const BodyVolume& a, const BodyVolume& b) { return a.center_m.x < b.center_m.x; });
  for (size_t i = 0; i < bodies.size(); ++i) {
    const BodyVolume& a = bodies[i];
    for (size_t j = i + 1; j < bodies.size() && bodies[j].center_m.x - a.center_m.x < a.radius_m + widest; ++j) {
      const float r = a.radius_m + bodies[j].radius_m;
      const vec2 d = a.center_m - bodies[j].center_m;
      if (glm::dot(d, d) < r * r) return true;
    }
  }
  return false;
}

}  // namespace foresight

#include "author/root_path.hpp"

#include "author/easing.hpp"

#include <cmath>

namespace foresight::author {

RootPath::RootPath(float duration_s, Placement end, float start_speed_mps, float end_speed_mps)
    : duration_s_(duration_s), end_(end) {
  // A cubic Bezier approximates a circular arc of angle a with handles 4/3 tan(a/4) r long, i.e.
  // Hermite tangents 4 tan(a/4)/a times the arc length: scaling the speeds by that keeps turning
  // paths round instead of pinched.
  const float a = std::abs(end.heading_rad);
  const float arc = a > 1e-4f ? 4.0f * std::tan(a / 4.0f) / a : 1.0f;
  start_tangent_ = rotate_ground(vec2(0, 1), 0.0f) * (start_speed_mps * duration_s * arc);
  end_tangent_ = rotate_ground(vec2(0, 1), end.heading_rad) * (end_speed_mps * duration_s * arc);
}

Placement RootPath::at(float t_s) const {
  const float s = clamp01(t_s / duration_s_);
  const vec2 p = hermite(vec2(0.0f), start_tangent_, end_.pos_m, end_tangent_, s);
  // Heading eases in and out: every clip starts and ends without turning, so any two clips can
  // follow each other.
  return {p, heading_.empty() ? end_.heading_rad * smoothstep01(s) : heading_.at(t_s)};
}

}  // namespace foresight::author

#include "world/synthetic_sweep.hpp"

#include <cmath>

namespace foresight {

std::vector<BodyVolume> synthetic_sweep(const SyntheticSweepSpec& spec) {
  std::vector<BodyVolume> out;
  if (spec.frames <= 0) return out;
  out.reserve(static_cast<std::size_t>(spec.frames));
  for (int i = 0; i < spec.frames; ++i) {
    const float t = spec.frames > 1 ? static_cast<float>(i) / static_cast<float>(spec.frames - 1) : 0.0f;
    const float s = spec.forward_m * t;
    vec2 p;
    float heading = 0.0f;
    if (std::abs(spec.turn_rad) < 1e-6f) {
      p = {0.0f, s};
    } else {
      // Arc of length s with curvature turn / length; heading h(s) = turn * s / length, and
      // d(x, z)/ds = (sin h, cos h) as in math/types.hpp.
      const float radius = spec.forward_m / spec.turn_rad;
      const float h = spec.turn_rad * t;
      heading = h;
      p = {radius * (1.0f - std::cos(h)), radius * std::sin(h)};
    }
    p.x += spec.sideways_m * t;
    out.push_back({p, spec.radius_m, spec.y_min_m, spec.y_max_m,
                   spec.half_length_m * vec2(std::sin(heading), std::cos(heading))});
  }
  return out;
}

}  // namespace foresight

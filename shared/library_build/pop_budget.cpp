#include "library_build/pop_budget.hpp"

#include "anim/fk.hpp"
#include "math/percentile.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace foresight {

void compute_pop_budget(MotionLibrary& lib) {
  const size_t n = static_cast<size_t>(lib.num_joints());
  std::vector<std::vector<vec3>> positions(lib.clips.size());
  for (size_t c = 0; c < lib.clips.size(); ++c) fk_clip_positions(lib.skeleton, lib.clips[c], positions[c]);
  // A frame's acceleration and speed are second and central differences over its neighbours; a
  // clip's first and last frames take the next inner frame's.
  const auto inner = [](int f, int frames) { return std::clamp(f, 1, std::max(1, frames - 2)); };
  const auto acceleration = [n](const std::vector<vec3>& p, size_t i) { return glm::length(p[i + n] - 2.0f * p[i] + p[i - n]); };

  lib.frame_acceleration_m.clear();
  std::vector<double> inner_frames;
  for (size_t c = 0; c < lib.clips.size(); ++c) {
    const int frames = lib.clips[c].num_frames;
    for (int f = 0; f < frames; ++f) {
      const size_t mid = static_cast<size_t>(inner(f, frames));
      float largest = 0.0f;
      if (static_cast<int>(mid) + 1 < frames)
        for (size_t j = 0; j < n; ++j) largest = std::max(largest, acceleration(positions[c], mid * n + j));
      lib.frame_acceleration_m.push_back(largest);
      if (f >= 1 && f + 1 < frames) inner_frames.push_back(largest);
    }
  }
  lib.pop_threshold_m = static_cast<float>(percentile(std::move(inner_frames), 99.9));

  // Per frame, the fastest turn that keeps every joint's own acceleration plus 2 x rate x its
  // ground speed within the budget; then floored, ramped and the least of its neighbours'.
  const float budget = kSteerBudgetShare * lib.pop_threshold_m;
  lib.steer_limit_rad.clear();
  for (size_t c = 0; c < lib.clips.size(); ++c) {
    const int frames = lib.clips[c].num_frames;
    const std::vector<vec3>& p = positions[c];
    const size_t first = lib.steer_limit_rad.size();
    for (int f = 0; f < frames; ++f) {
      const size_t mid = static_cast<size_t>(inner(f, frames));
      float limit = kPi;
      if (static_cast<int>(mid) + 1 < frames)
        for (size_t j = 0; j < n; ++j) {
          const size_t i = mid * n + j;
          const vec3 speed = 0.5f * (p[i + n] - p[i - n]);
          const float ground_speed = std::hypot(speed.x, speed.z);
          const float room = std::max(0.0f, budget - acceleration(p, i));
          if (ground_speed > 1e-6f) limit = std::min(limit, room / (2.0f * ground_speed));
        }
      lib.steer_limit_rad.push_back(std::max(limit, kSteerLimitFloor_rad));
    }
    float* l = lib.steer_limit_rad.data() + first;
    for (int f = 1; f < frames; ++f) l[f] = std::min(l[f], l[f - 1] + kSteerLimitRamp_rad);
    for (int f = frames - 2; f >= 0; --f) l[f] = std::min(l[f], l[f + 1] + kSteerLimitRamp_rad);
    // A frame's shown acceleration spans its neighbours: each frame keeps the least of the three
    // (the clip's ends their own and their one neighbour's).
    const std::vector<float> ramped(l, l + frames);
    for (int f = 0; f < frames; ++f)
      l[f] = std::min({ramped[static_cast<size_t>(std::max(f - 1, 0))], ramped[static_cast<size_t>(f)],
                       ramped[static_cast<size_t>(std::min(f + 1, frames - 1))]});
  }
}

}  // namespace foresight

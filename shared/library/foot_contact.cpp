#include "library/foot_contact.hpp"

#include "anim/canonical_skeleton.hpp"
#include "anim/fk.hpp"

#include <algorithm>
#include <cmath>

namespace foresight {

int foot_heel_joint(int foot) { return foot == 0 ? kCanonLeftFoot : kCanonRightFoot; }
int foot_ball_joint(int foot) { return foot == 0 ? kCanonLeftToeBase : kCanonRightToeBase; }

void clip_foot_contact(const Skeleton& skeleton, const Clip& clip, std::vector<uint8_t>& out, float& max_step_m) {
  std::vector<vec3> pos;
  fk_clip_positions(skeleton, clip, pos);
  const int n = clip.num_joints;
  for (size_t i = static_cast<size_t>(n); i < pos.size(); ++i)
    max_step_m = std::max(max_step_m, glm::length(pos[i] - pos[i - static_cast<size_t>(n)]));
  const int frames = clip.num_frames;
  const float dt = clip.fps > 0.0f ? 1.0f / clip.fps : 1.0f / 30.0f;
  const auto at = [&](int f, int j) { return pos[static_cast<size_t>(f) * static_cast<size_t>(n) + static_cast<size_t>(j)]; };
  const size_t first = out.size();
  out.resize(first + static_cast<size_t>(frames), 0);
  if (frames <= 0 || n <= kCanonRightToeBase) return;
  for (int foot = 0; foot < 2; ++foot)
    for (const auto& [joint, bit] : {std::pair{foot_heel_joint(foot), foot_heel_bit(foot)},
                                     std::pair{foot_ball_joint(foot), foot_ball_bit(foot)}}) {
      float lowest = at(0, joint).y;
      for (int f = 1; f < frames; ++f) lowest = std::min(lowest, at(f, joint).y);
      for (int f = 0; f < frames; ++f) {
        // Speed over the neighbouring frames (one-sided at the ends).
        const int a = std::max(0, f - 1), b = std::min(frames - 1, f + 1);
        const vec3 v = b > a ? (at(b, joint) - at(a, joint)) / (static_cast<float>(b - a) * dt) : vec3(0.0f);
        if (at(f, joint).y - lowest < kContactHeight_m && std::hypot(v.x, v.z) < kContactSpeed_mps &&
            std::abs(v.y) < kContactRise_mps)
          out[first + static_cast<size_t>(f)] |= bit;
      }
    }
}

}  // namespace foresight

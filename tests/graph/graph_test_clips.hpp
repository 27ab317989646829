#pragma once
// Synthetic clips for graph tests: a 3-joint "walker" whose leg swings with a fixed period while
// the pelvis moves forward, so poses repeat exactly every period.
#include "anim/clip.hpp"

#include <cmath>

namespace foresight::test {

inline Skeleton walker_skeleton() {
  Skeleton s;
  s.joint_names = {"Hips", "LeftUpLeg", "RightUpLeg", "LeftFoot", "RightFoot"};
  s.parents = {kNoParent, 0, 0, 1, 2};
  s.rest_offsets_m = {vec3(0, 0.9f, 0), vec3(0.1f, 0, 0), vec3(-0.1f, 0, 0), vec3(0, -0.85f, 0),
                      vec3(0, -0.85f, 0)};
  s.is_end_site = {false, false, false, false, false};
  return s;
}

/// `frames` frames of a swing with period `period` frames, starting at phase `phase_frames`,
/// walking forward at 1.2 m/s.
inline Clip walker_clip(const Skeleton& s, const char* name, int frames, int period,
                        int phase_frames) {
  Clip c;
  c.name = name;
  c.resize(s, frames);
  for (int f = 0; f < frames; ++f) {
    const float phase = kTwoPi * static_cast<float>(f + phase_frames) / static_cast<float>(period);
    c.frame_pos(f)[0] = vec3(0, 0.9f + 0.02f * std::cos(2 * phase), 1.2f * f / 30.0f);
    c.frame_rot(f)[1] = glm::angleAxis(0.5f * std::sin(phase), vec3(1, 0, 0));
    c.frame_rot(f)[2] = glm::angleAxis(-0.5f * std::sin(phase), vec3(1, 0, 0));
  }
  return c;
}

}  // namespace foresight::test

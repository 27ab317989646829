#pragma once
// Checks every library must pass, whatever built it (default manifest, BVH folder, synthetic).
#include "anim/fk.hpp"
#include "library/playback.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace foresight::test {

inline std::vector<vec3> world_positions(const MotionLibrary& lib, const PlaybackState& s) {
  Pose pose;
  playback_pose(lib, s, pose);
  std::vector<vec3> pos(static_cast<size_t>(lib.num_joints()));
  std::vector<quat> rot(static_cast<size_t>(lib.num_joints()));
  fk_pose(lib.skeleton, pose.local_pos_m, pose.local_rot, pos, rot);
  return pos;
}

inline float max_distance(const std::vector<vec3>& a, const std::vector<vec3>& b) {
  float d = 0;
  for (size_t j = 0; j < a.size(); ++j) d = std::max(d, glm::length(a[j] - b[j]));
  return d;
}

/// Plays every edge from a placement with a non-zero heading and checks that the pose is
/// continuous: the successor's first frame equals the predecessor's boundary pose, and the joint
/// jump across the edge is no larger than `slack` times the fastest joint motion of the frames
/// around it plus `floor_m`. Returns the worst ratio seen.
inline void expect_continuous_edges(const MotionLibrary& lib, float slack, float floor_m) {
  const Placement where{vec2(3.0f, -2.0f), 0.7f};
  float worst_jump = 0;
  std::string worst;
  for (size_t t = 0; t < lib.graph.transitions.size(); ++t) {
    const Transition& tr = lib.graph.transitions[t];
    const int a_frames = lib.graph.segments[tr.from].num_frames();
    PlaybackState a{tr.from, a_frames - 1, where, -1};
    const auto last = world_positions(lib, a);
    a.frame = std::max(0, a_frames - 2);
    const float a_step = max_distance(world_positions(lib, a), last);
    a.frame = a_frames;  // the boundary pose
    const auto boundary = world_positions(lib, a);
    a.frame = a_frames - 1;
    PlaybackState b = a;
    playback_take(lib, b, static_cast<int>(t));
    const auto first = world_positions(lib, b);
    b.frame = std::min(1, lib.graph.segments[tr.to].num_frames());
    const float b_step = max_distance(first, world_positions(lib, b));
    EXPECT_LT(max_distance(first, boundary), 1e-3f)
        << lib.graph.segments[tr.from].name << " -> " << lib.graph.segments[tr.to].name;
    const float jump = max_distance(first, last);
    const float bound = slack * std::max(a_step, b_step) + floor_m;
    EXPECT_LE(jump, bound) << lib.graph.segments[tr.from].name << " -> "
                           << lib.graph.segments[tr.to].name << " jumps " << jump << " m";
    if (jump > worst_jump) worst_jump = jump, worst = lib.graph.segments[tr.from].name + " -> " +
                                                     lib.graph.segments[tr.to].name;
  }
  std::printf("[          ] %zu edges, largest joint jump across an edge %.4f m (%s)\n",
              lib.graph.transitions.size(), worst_jump, worst.c_str());
}

}  // namespace foresight::test

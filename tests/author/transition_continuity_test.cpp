// Every declared transition joins two equal poses: A's last frame and B's first frame, once B is
// placed where A's root track ends (how the motion graph plays them).
#include "author/author_test_support.hpp"

#include <gtest/gtest.h>

#include <set>

namespace foresight::author::testing {
namespace {

TEST(TransitionContinuity, EveryDeclaredTransitionJoinsTheSamePose) {
  // 2 cm: well under what a 4-8 frame blend hides; by construction the gap is float noise plus
  // the heading extraction's sensitivity to pelvis tilt differences between families (< 1 cm).
  float worst = 0.0f;
  std::string worst_pair;
  for (const DeclaredTransition& t : library().transitions) {
    const float gap = transition_gap_m(find_clip(t.from)->clip, find_clip(t.to)->clip);
    EXPECT_LT(gap, 0.02f) << t.from << " -> " << t.to;
    if (gap > worst) worst = gap, worst_pair = t.from + " -> " + t.to;
  }
  std::printf("[ info ] %zu transitions, worst gap %.4f m (%s)\n", library().transitions.size(),
              worst, worst_pair.c_str());
}

TEST(TransitionContinuity, LoopingClipsEndWhereTheyStart) {
  for (const char* name : {"idle", "crouch_idle", "fight_stance"})
    EXPECT_LT(transition_gap_m(find_clip(name)->clip, find_clip(name)->clip), 0.01f) << name;
  // Gaits loop over two steps: left, right, left...
  for (const char* gait : {"walk", "walk_slow", "run", "crouch_walk"}) {
    const std::string l = std::string(gait) + "_l", r = std::string(gait) + "_r";
    EXPECT_LT(transition_gap_m(find_clip(l)->clip, find_clip(r)->clip), 0.01f) << l;
    EXPECT_LT(transition_gap_m(find_clip(r)->clip, find_clip(l)->clip), 0.01f) << r;
  }
}

TEST(TransitionContinuity, ChainedPlaybackStaysContinuous) {
  // Play a route the avatar would take, placing each clip at the previous one's last placement,
  // and check that the pelvis never jumps between consecutive played frames.
  const std::vector<std::string> route = {
      "idle", "walk_start_l", "walk_r", "walk_turn_left_45_l", "walk_turn_left_45_r",
      "walk_to_slow_l", "walk_slow_r", "slow_to_walk_l", "walk_to_run_r", "run_l",
      "run_turn_right_22_r", "run_to_walk_l", "walk_to_crouch_walk_r", "crouch_walk_l",
      "crouch_walk_turn_left_22_r", "crouch_walk_to_walk_l", "walk_turn_right_22_r", "walk_stop_l",
      "idle_turn_180", "side_step_left", "idle_to_stance", "fight_stance", "kick_left_front_high",
      "fight_stance", "stance_to_idle"};
  std::set<std::pair<std::string, std::string>> declared;
  for (const DeclaredTransition& t : library().transitions) declared.insert({t.from, t.to});
  for (size_t i = 0; i + 1 < route.size(); ++i)
    EXPECT_TRUE(declared.count({route[i], route[i + 1]})) << route[i] << " -> " << route[i + 1];
  const Chain chain = chain_clips(route);
  for (int f = 1; f < chain.num_frames; ++f)
    EXPECT_LT(glm::length(chain.at(f, 0) - chain.at(f - 1, 0)), 0.15f) << "frame " << f;
  // No joint pops across boundaries either: the same acceleration bound as within a clip
  // (locomotion_quality_test.cpp), here without blending, so the boundaries must match in velocity
  // too, not only in pose.
  float worst = 0.0f;
  int worst_frame = -1;
  for (int f = 1; f + 1 < chain.num_frames; ++f)
    for (int j = 0; j < chain.num_joints; ++j) {
      const float a = glm::length(chain.at(f + 1, j) - 2.0f * chain.at(f, j) + chain.at(f - 1, j));
      if (a > worst) worst = a, worst_frame = f;
    }
  EXPECT_LT(worst, 0.2f) << "at chained frame " << worst_frame;
  // The turns compose: +45 +45 -22.5 +22.5 -22.5 +180 = 247.5 deg, i.e. -112.5.
  const float heading =
      degrees(wrap_angle(chain.root.back().heading_rad - chain.root.front().heading_rad));
  EXPECT_NEAR(heading, -112.5f, 3.0f);
}

}  // namespace
}  // namespace foresight::author::testing

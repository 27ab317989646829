// Every declared transition joins two equal poses: A's last frame and B's first frame, once B is
// placed where A's root track ends (how the motion graph plays them).
#include "author/author_test_support.hpp"

#include <gtest/gtest.h>

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
  for (const char* name : {"idle", "crouch_idle", "fight_stance", "walk", "run", "crouch_walk"})
    EXPECT_LT(transition_gap_m(find_clip(name)->clip, find_clip(name)->clip), 0.01f) << name;
}

TEST(TransitionContinuity, ChainedPlaybackStaysContinuous) {
  // Play a route the avatar would take, placing each clip at the previous one's last placement,
  // and check that the pelvis never jumps between consecutive played frames.
  const char* route[] = {"idle", "walk_start", "walk", "walk_turn_left_90", "walk_to_run", "run",
                         "run_turn_right_45", "run_to_walk", "walk_to_crouch_walk", "crouch_walk",
                         "crouch_walk_to_walk", "walk_turn_right_45", "walk_stop", "idle_to_stance",
                         "fight_stance", "kick_left_front_high", "fight_stance", "stance_to_idle"};
  Placement at_start{};
  vec3 previous(0.0f);
  bool first = true;
  for (const char* name : route) {
    const Clip& clip = find_clip(name)->clip;
    const std::vector<vec3> pos = clip_positions(clip);
    const std::vector<Placement> track = clip_root_track(clip);
    const Placement place = at_start.compose(track.front().inverse());
    for (int f = 0; f + 1 < clip.num_frames; ++f) {
      const vec3 pelvis = place.apply(at(pos, clip, f, 0));
      if (!first) { EXPECT_LT(glm::length(pelvis - previous), 0.15f) << name << " frame " << f; }
      previous = pelvis;
      first = false;
    }
    at_start = place.compose(track.back());
  }
}

}  // namespace
}  // namespace foresight::author::testing

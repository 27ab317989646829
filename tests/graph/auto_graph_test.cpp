#include "graph_build/auto_graph.hpp"

#include "graph_build/graph_edit.hpp"
#include "graph_test_clips.hpp"

#include <gtest/gtest.h>

namespace foresight {
namespace {

TEST(AutoGraph, PeriodicClipLoopsOntoItselfOnePeriodBack) {
  const Skeleton s = test::walker_skeleton();
  const Clip clips[] = {test::walker_clip(s, "walk", 120, 30, 0)};
  MotionGraph g;
  AutoGraphReport report;
  std::string error;
  AutoGraphOptions o;
  o.candidate_stride = 1;
  ASSERT_TRUE(graph_build_automatic(s, clips, o, g, &report, error)) << error;
  EXPECT_GT(report.local_minima, 0);
  // Every jump inside a periodic clip goes back or forward by a whole number of periods.
  int jumps = 0;
  for (const Transition& t : g.transitions) {
    if (t.blend_frames == 0) continue;  // clip-order link
    ++jumps;
    int delta = g.segments[t.from].end_frame - g.segments[t.to].first_frame;
    // A clip join leaves from the last frame (119) as if the clip went on to frame 120.
    if (g.segments[t.from].end_frame == 119 && g.segments[t.to].first_frame == 0) ++delta;
    EXPECT_EQ(delta % 30, 0) << "jump of " << delta << " frames";
  }
  EXPECT_GT(jumps, 0);
  EXPECT_EQ(largest_strongly_connected_component(g).size(), static_cast<size_t>(g.num_segments()));
}

TEST(AutoGraph, PhaseShiftedClipsConnectAtMatchingPhases) {
  const Skeleton s = test::walker_skeleton();
  const Clip clips[] = {test::walker_clip(s, "a", 90, 30, 0), test::walker_clip(s, "b", 90, 30, 10)};
  MotionGraph g;
  AutoGraphReport report;
  std::string error;
  ASSERT_TRUE(graph_build_automatic(s, clips, AutoGraphOptions{}, g, &report, error)) << error;
  int cross = 0;
  for (const Transition& t : g.transitions) {
    const Segment& from = g.segments[t.from];
    const Segment& to = g.segments[t.to];
    if (from.clip == to.clip) continue;
    ++cross;
    // Frame f of a is at phase f; frame f of b at phase f + 10.
    const int phase_from = from.end_frame + (from.clip == 1 ? 10 : 0);
    const int phase_to = to.first_frame + (to.clip == 1 ? 10 : 0);
    EXPECT_EQ((phase_from - phase_to + 300) % 30, 0);
  }
  EXPECT_GT(cross, 0);
  EXPECT_EQ(report.segments, g.num_segments());
}

TEST(AutoGraph, DissimilarClipsAreRefusedWithAReason) {
  const Skeleton s = test::walker_skeleton();
  // The legs sweep once from back to front: no pose repeats, so nothing can loop.
  Clip sweep = test::walker_clip(s, "sweep", 40, 30, 0);
  for (int f = 0; f < sweep.num_frames; ++f) {
    const float angle = -1.5f + 3.0f * static_cast<float>(f) / 39.0f;
    sweep.frame_rot(f)[1] = glm::angleAxis(angle, vec3(1, 0, 0));
    sweep.frame_rot(f)[2] = glm::angleAxis(angle, vec3(1, 0, 0));
  }
  const Clip clips[] = {sweep};
  MotionGraph g;
  std::string error;
  AutoGraphOptions o;
  o.threshold_rms_m = 0.01f;
  EXPECT_FALSE(graph_build_automatic(s, clips, o, g, nullptr, error));
  EXPECT_NE(error.find("threshold_rms_m"), std::string::npos) << error;
}

// Two half-period steps cut from one walk (as takes are cut into left and right steps): each is
// shorter than a window, so no Kovar transition leaves it, but each one's end continues into the
// other's start: the clip joins chain them into a walk that goes on for ever. A clip whose end
// does not match (here: a step frozen mid-swing) joins nothing.
TEST(AutoGraph, TakesCutIntoStepsChainEndToStart) {
  const Skeleton s = test::walker_skeleton();
  // 16 frames at period 30: frames 0..15 and 15..30 of the walk (the boundary pose shared).
  const Clip left = test::walker_clip(s, "left", 16, 30, 0), right = test::walker_clip(s, "right", 16, 30, 15);
  Clip frozen = test::walker_clip(s, "frozen", 16, 30, 7);
  for (int f = 0; f < frozen.num_frames; ++f) frozen.frame_rot(f)[1] = frozen.frame_rot(f)[2] = glm::angleAxis(0.5f, vec3(1, 0, 0));
  const Clip clips[] = {left, right, frozen};
  AutoGraphOptions o;
  o.prune_to_largest_component = false;
  MotionGraph g;
  AutoGraphReport report;
  std::string error;
  ASSERT_TRUE(graph_build_automatic(s, clips, o, g, &report, error)) << error;
  auto joined = [&](const char* from_clip, const char* to_clip) {
    for (const Transition& t : g.transitions) {
      const Segment& a = g.segments[static_cast<size_t>(t.from)];
      const Segment& b = g.segments[static_cast<size_t>(t.to)];
      if (clips[a.clip].name == from_clip && clips[b.clip].name == to_clip && a.end_frame == 15 && b.first_frame == 0)
        return t.blend_frames == kClipJoinBlendFrames;
    }
    return false;
  };
  EXPECT_TRUE(joined("left", "right"));
  EXPECT_TRUE(joined("right", "left"));
  EXPECT_FALSE(joined("frozen", "left"));
  EXPECT_FALSE(joined("left", "frozen"));
  EXPECT_GE(report.clip_joins, 2);
  // Pruned, the two steps are a loop and the frozen clip is gone.
  MotionGraph pruned;
  ASSERT_TRUE(graph_build_automatic(s, clips, AutoGraphOptions{}, pruned, nullptr, error)) << error;
  for (const Segment& seg : pruned.segments) EXPECT_NE(clips[seg.clip].name, "frozen");
}

TEST(AutoGraph, MismatchedFrameRatesAreRefused) {
  const Skeleton s = test::walker_skeleton();
  Clip a = test::walker_clip(s, "a", 40, 30, 0), b = test::walker_clip(s, "b", 40, 30, 0);
  b.fps = 60;
  const Clip clips[] = {a, b};
  MotionGraph g;
  std::string error;
  EXPECT_FALSE(graph_build_automatic(s, clips, AutoGraphOptions{}, g, nullptr, error));
  EXPECT_NE(error.find("fps"), std::string::npos);
}

}  // namespace
}  // namespace foresight

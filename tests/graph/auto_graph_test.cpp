#include "graph/auto_graph.hpp"

#include "graph/graph_edit.hpp"
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
    const int delta = g.segments[t.from].end_frame - g.segments[t.to].first_frame;
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

#include "graph_build/declared_graph.hpp"
#include "graph_build/graph_edit.hpp"
#include "graph/motion_graph.hpp"

#include <gtest/gtest.h>

namespace foresight {
namespace {

MotionGraph graph_with_edges(int n, std::vector<std::pair<int, int>> edges) {
  MotionGraph g;
  for (int i = 0; i < n; ++i) g.segments.push_back({"s" + std::to_string(i), 0, 0, 1, kTagNone});
  for (auto [a, b] : edges) g.transitions.push_back({a, b, 0});
  g.finalize();
  return g;
}

TEST(MotionGraph, SuccessorsAreSortedAndDeduplicated) {
  const MotionGraph g = graph_with_edges(3, {{0, 2}, {0, 1}, {0, 2}, {2, 0}});
  ASSERT_EQ(g.successors(0).size(), 2u);
  EXPECT_EQ(g.successors(0)[0].to, 1);
  EXPECT_EQ(g.successors(0)[1].to, 2);
  EXPECT_TRUE(g.successors(1).empty());
  EXPECT_EQ(g.successors(2).size(), 1u);
}

TEST(GraphEdit, LargestSccDropsDeadEndsAndUnreachableSegments) {
  // 0 <-> 1 <-> 2 is a cycle of three; 3 is a dead end after 2; 4 only leads into the cycle.
  const MotionGraph g = graph_with_edges(5, {{0, 1}, {1, 2}, {2, 0}, {2, 3}, {4, 0}});
  EXPECT_EQ(largest_strongly_connected_component(g), (std::vector<int>{0, 1, 2}));
  const MotionGraph kept = graph_keep_segments(g, {0, 1, 2});
  EXPECT_EQ(kept.num_segments(), 3);
  EXPECT_EQ(kept.transitions.size(), 3u);
}

TEST(GraphEdit, LongChainDoesNotOverflowTheStack) {
  // A 200k-segment ring: a recursive Tarjan would blow the stack here.
  const int n = 200000;
  std::vector<std::pair<int, int>> edges;
  for (int i = 0; i < n; ++i) edges.push_back({i, (i + 1) % n});
  EXPECT_EQ(largest_strongly_connected_component(graph_with_edges(n, edges)).size(),
            static_cast<size_t>(n));
}

TEST(DeclaredGraph, UnknownClipNameIsReported) {
  Skeleton s;
  s.joint_names = {"Hips"};
  s.parents = {kNoParent};
  s.rest_offsets_m = {vec3(0)};
  s.is_end_site = {false};
  Clip a;
  a.name = "walk";
  a.resize(s, 10);
  MotionGraph g;
  std::string error;
  const DeclaredTransition bad[] = {{"walk", "walk", 4}, {"walk", "flyy", 4}};
  EXPECT_FALSE(graph_from_declared(std::span(&a, 1), {}, bad, g, error));
  EXPECT_NE(error.find("transition 1"), std::string::npos) << error;
  EXPECT_NE(error.find("flyy"), std::string::npos) << error;
  const DeclaredTransition good[] = {{"walk", "walk", 4}};
  ASSERT_TRUE(graph_from_declared(std::span(&a, 1), {}, good, g, error)) << error;
  EXPECT_EQ(g.segments[0].end_frame, 9);  // the last frame is the boundary pose
  EXPECT_EQ(g.successors(0)[0].blend_frames, 4);
}

}  // namespace
}  // namespace foresight

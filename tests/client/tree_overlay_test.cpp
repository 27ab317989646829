// The tree overlay's ghost poses (client/tree_overlay.*) without a window: which nodes get ghosts,
// from which placement, entered by which transition.
#include "tree_overlay.hpp"

#include "library_build/library_source.hpp"

#include <gtest/gtest.h>

namespace foresight::client {
namespace {

const MotionLibrary& library() {
  static const MotionLibrary lib = motion_library_default();
  return lib;
}

// A root playing segment `root` at `start`, one chosen child per step of `chosen`, and one
// ordinary child of the root (its first successor).
protocol::TreeView tree_of(int root, const Placement& start, const std::vector<int>& chosen) {
  const MotionLibrary& lib = library();
  protocol::TreeView t;
  t.origin_m = start.pos_m;
  Placement at = start;
  int segment = root;
  for (size_t i = 0; i <= chosen.size(); ++i) {
    if (i > 0) segment = chosen[i - 1];
    const Placement end = at.compose(lib.segment_motion[static_cast<size_t>(segment)].end);
    t.end_m.push_back(end.pos_m);
    t.parent.push_back(i == 0 ? protocol::kTreeNoParent : static_cast<uint16_t>(i - 1));
    t.depth.push_back(static_cast<uint8_t>(i));
    t.chosen.push_back(i == 0 ? 0 : 1);
    t.segment.push_back(static_cast<uint16_t>(segment));
    t.start_heading_rad.push_back(at.heading_rad);
    at = end;
  }
  const int other = lib.graph.successors(root)[0].to;
  t.end_m.push_back(start.compose(lib.segment_motion[static_cast<size_t>(root)].end)
                        .compose(lib.segment_motion[static_cast<size_t>(other)].end)
                        .pos_m);
  t.parent.push_back(0);
  t.depth.push_back(1);
  t.chosen.push_back(0);
  t.segment.push_back(static_cast<uint16_t>(other));
  t.start_heading_rad.push_back(t.start_heading_rad[0]);
  return t;
}

TEST(TreeOverlay, GhostsFollowTheChosenBranchFromTheLibrary) {
  const MotionLibrary& lib = library();
  const int root = 0;
  const auto first = lib.graph.successors(root);
  ASSERT_FALSE(first.empty());
  const int a = first.back().to;
  const auto second = lib.graph.successors(a);
  ASSERT_FALSE(second.empty());
  const int b = second[0].to;
  const Placement start{vec2(2.0f, -3.0f), 0.8f};
  const protocol::TreeView tree = tree_of(root, start, {a, b});

  std::vector<PlaybackState> ghosts;
  tree_ghost_states(lib, tree, ghosts);
  // Two chosen nodes below the root: the middle and the last frame of each (the root is the
  // avatar itself, the ordinary child gets none).
  ASSERT_EQ(ghosts.size(), 2u * kGhostFramesPerNode);
  const Placement a_start = start.compose(lib.segment_motion[static_cast<size_t>(root)].end);
  for (int k = 0; k < 2; ++k) {
    const PlaybackState& g = ghosts[static_cast<size_t>(k)];
    EXPECT_EQ(g.segment, a);
    EXPECT_LT(glm::length(g.segment_start.pos_m - a_start.pos_m), 1e-4f);
    EXPECT_NEAR(g.segment_start.heading_rad, a_start.heading_rad, 1e-5f);
    EXPECT_EQ(g.incoming_transition, lib.graph.first_transition[root] + static_cast<int>(first.size()) - 1);
    EXPECT_EQ(lib.graph.transitions[static_cast<size_t>(g.incoming_transition)].to, a);
  }
  const int frames_a = lib.graph.segments[static_cast<size_t>(a)].num_frames();
  EXPECT_EQ(ghosts[0].frame, frames_a / 2);
  EXPECT_EQ(ghosts[1].frame, frames_a - 1);
  EXPECT_EQ(ghosts[2].segment, b);
  EXPECT_EQ(ghosts[2].incoming_transition, lib.graph.first_transition[a]);
  // Ghost poses are ordinary playback states: the pose at the end of a's clip stands where b starts.
  EXPECT_LT(glm::length(playback_next_start(lib, ghosts[1]).pos_m - ghosts[2].segment_start.pos_m), 1e-4f);
}

TEST(TreeOverlay, NodesOutsideTheLibraryGetNoGhost) {
  const MotionLibrary& lib = library();
  const int a = lib.graph.successors(0)[0].to;
  protocol::TreeView tree = tree_of(0, Placement{}, {a});
  std::vector<PlaybackState> ghosts;
  tree_ghost_states(lib, tree, ghosts);
  EXPECT_EQ(ghosts.size(), static_cast<size_t>(kGhostFramesPerNode));
  tree.segment[1] = static_cast<uint16_t>(lib.graph.num_segments());  // a library we do not have
  tree_ghost_states(lib, tree, ghosts);
  EXPECT_TRUE(ghosts.empty());
  protocol::TreeView empty;
  tree_ghost_states(lib, empty, ghosts);
  EXPECT_TRUE(ghosts.empty());
}

}  // namespace
}  // namespace foresight::client

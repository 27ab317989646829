#include "lookahead/motion_tree.hpp"
#include "lookahead/lookahead_avatar.hpp"
#include "support/segments.hpp"

#include "library/foreign_capture.hpp"
#include "lookahead_fixture.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <vector>

namespace foresight {
namespace {

using test::default_library;
using test::loaded_scene;

using test::walk_segment;

MotionTreeConfig config_for(Strategy s, int max_nodes = 4096) {
  MotionTreeConfig c;
  c.strategy = s;
  c.max_nodes = max_nodes;
  return c;
}

// The arena's open middle, facing +Z.
const Placement kOpen{vec2(0.0f, -4.0f), 0.0f};

std::vector<MotionTreeNode> snapshot(const MotionTree& t) {
  std::vector<MotionTreeNode> out;
  t.for_each_node([&](int, const MotionTreeNode& n) { out.push_back(n); });
  return out;
}

TEST(MotionTree, SameInputAndBudgetGiveTheSameTreeBitForBit) {
  const auto& lib = default_library();
  const auto& arena = loaded_scene("arena");
  for (int s = 0; s < kNumStrategies; ++s) {
    MotionTree a(lib, arena.world, config_for(static_cast<Strategy>(s)));
    MotionTree b(lib, arena.world, config_for(static_cast<Strategy>(s)));
    for (MotionTree* t : {&a, &b}) {
      t->reset(walk_segment(lib), kOpen);
      t->set_command(vec2(1.0f, 1.0f), kOpen);
      t->grow(GrowBudget::expansions(500));
      t->set_command(vec2(-1.0f, 0.2f), kOpen);
      t->grow(GrowBudget::expansions(300));
    }
    const auto na = snapshot(a), nb = snapshot(b);
    ASSERT_EQ(na.size(), nb.size()) << strategy_name(static_cast<Strategy>(s));
    ASSERT_GT(na.size(), 20u);
    EXPECT_EQ(std::memcmp(na.data(), nb.data(), na.size() * sizeof(MotionTreeNode)), 0)
        << strategy_name(static_cast<Strategy>(s));
  }
}

// Players' trees leave the fighters' footwork (half steps forward) out; a tree that allows it
// (the fighters') offers it from standing.
TEST(MotionTree, FootworkIsLeftOutOfPlayersTreesByDefault) {
  const auto& lib = default_library();
  const auto& arena = loaded_scene("arena");
  const int idle = find_fallback_segment(lib);
  ASSERT_GE(idle, 0);
  const auto footwork_nodes = [&](const MotionTreeConfig& config) {
    MotionTree t(lib, arena.world, config);
    t.reset(idle, kOpen);
    t.set_command(vec2(0.0f, 1.0f), kOpen);
    t.grow(GrowBudget::expansions(500));
    int n = 0;
    t.for_each_node([&](int, const MotionTreeNode& node) {
      if (node.transition < 0) return;
      const int segment = lib.graph.transitions[static_cast<size_t>(node.transition)].to;
      if (lib.graph.segments[static_cast<size_t>(segment)].tags & kTagFootwork) ++n;
    });
    return n;
  };
  MotionTreeConfig players = config_for(Strategy::kCommand);
  EXPECT_EQ(footwork_nodes(players), 0);
  MotionTreeConfig fighters = players;
  fighters.excluded_tags &= ~static_cast<uint32_t>(kTagFootwork);
  EXPECT_GT(footwork_nodes(fighters), 0);
}

TEST(MotionTree, EveryNodeIsCollisionFreeAndPlacedAtItsParentsEnd) {
  const auto& lib = default_library();
  const auto& maze = loaded_scene("maze");
  MotionTree t(lib, maze.world, config_for(Strategy::kBreadthFirst));
  const SpawnPoint& spawn = maze.scene.spawns.front();
  t.reset(test::idle_segment(lib), {spawn.pos_m, spawn.heading_rad});
  t.set_command(vec2(1, 0), {spawn.pos_m, spawn.heading_rad});
  const GrowResult r = t.grow(GrowBudget::expansions(3000));
  EXPECT_GT(r.nodes_added, 10);
  EXPECT_LT(r.nodes_added, r.expansions);  // the maze's walls reject some placements
  int checked = 0;
  t.for_each_node([&](int i, const MotionTreeNode& n) {
    const Placement end = t.start_of(i).compose(lib.segment_motion[static_cast<size_t>(t.segment_of(i))].end);
    EXPECT_NEAR(glm::length(n.end.pos_m - end.pos_m), 0.0f, 1e-5f);
    EXPECT_NEAR(std::remainder(n.end.heading_rad - end.heading_rad, 2.0f * kPi), 0.0f, 1e-5f);
    if (n.parent < 0) return;
    EXPECT_EQ(t.start_of(i).pos_m, t.node(n.parent).end.pos_m);
    EXPECT_TRUE(segment_feasible(maze.world, lib.segment_shapes[t.segment_of(i)], t.start_of(i)));
    EXPECT_EQ(lib.graph.transitions[n.transition].from, t.segment_of(n.parent));
    ++checked;
  });
  EXPECT_EQ(checked + 1, t.num_nodes());
}

TEST(MotionTree, AdvancingTheRootKeepsOnlyTheChosenBranch) {
  const auto& lib = default_library();
  const auto& arena = loaded_scene("arena");
  MotionTree t(lib, arena.world, config_for(Strategy::kCommand));
  t.reset(walk_segment(lib), kOpen);
  t.set_command(vec2(0, 1), kOpen);
  t.grow(GrowBudget::expansions(2000));
  const int child = t.select_child();
  ASSERT_GE(child, 0);
  int branch = 0;
  std::vector<int> stack{child};
  while (!stack.empty()) {
    const int n = stack.back();
    stack.pop_back();
    ++branch;
    for (int c = t.node(n).first_child; c >= 0; c = t.node(c).next_sibling) stack.push_back(c);
  }
  const int before = t.num_nodes();
  const MotionTreeNode chosen = t.node(child);
  const int chosen_segment = t.segment_of(child);
  const Placement chosen_start = t.start_of(child);
  EXPECT_EQ(t.advance_root(child), chosen.transition);
  // The chosen child is the root (the nodes were renumbered from 0, in their order).
  EXPECT_EQ(t.root(), 0);
  EXPECT_EQ(t.node(t.root()).end.pos_m, chosen.end.pos_m);
  EXPECT_EQ(t.segment_of(t.root()), chosen_segment);
  EXPECT_EQ(t.start_of(t.root()).pos_m, chosen_start.pos_m);
  EXPECT_EQ(t.start_of(t.root()).heading_rad, chosen_start.heading_rad);
  EXPECT_EQ(t.num_nodes(), branch);
  EXPECT_LT(t.num_nodes(), before);
  EXPECT_EQ(t.node(t.root()).depth, 0);
  int counted = 0;
  t.for_each_node([&](int, const MotionTreeNode&) { ++counted; });
  EXPECT_EQ(counted, t.num_nodes());
  // The tree holds its live nodes and no more; growing again never exceeds the cap.
  EXPECT_EQ(t.node_capacity(), (t.num_nodes() + 63) / 64 * 64);
  t.grow(GrowBudget::expansions(100000));
  EXPECT_LE(t.num_nodes(), t.config().max_nodes);
}

// Node storage follows the work (issue 20): a small tree holds a few chunks; it takes more as the
// budget pays for more nodes and stops at the chunk that holds the cap, also when the cap is not a
// multiple of the chunk.
TEST(MotionTree, NodeStorageGrowsWithTheTreeUpToTheCap) {
  const auto& lib = default_library();
  const auto& arena = loaded_scene("arena");
  MotionTree t(lib, arena.world, config_for(Strategy::kCommand, 3000));
  t.reset(walk_segment(lib), kOpen);
  t.set_command(vec2(0.0f, 1.0f), kOpen);
  t.grow(GrowBudget::expansions(40));
  EXPECT_GE(t.node_capacity(), t.num_nodes());
  EXPECT_LE(t.node_capacity(), 512) << "a tree of " << t.num_nodes() << " nodes";
  const size_t small_bytes = t.node_bytes();
  EXPECT_LT(small_bytes, 3000u * sizeof(MotionTreeNode) / 4);
  EXPECT_NE(t.grow(GrowBudget::expansions(1000000)).status & kGrowOutOfNodes, 0);
  EXPECT_GE(t.node_capacity(), 3000);
  EXPECT_LT(t.node_capacity(), 3000 + MotionNodePool::kChunkNodes);
  EXPECT_LE(t.num_nodes(), 3000);
  EXPECT_GT(t.num_nodes(), 2900);
  EXPECT_GT(t.node_bytes(), 4 * small_bytes);
  // Every node is still reachable and placed where its parent ends after the moves.
  int counted = 0;
  t.for_each_node([&](int i, const MotionTreeNode& n) {
    ++counted;
    const Placement end = t.start_of(i).compose(lib.segment_motion[static_cast<size_t>(t.segment_of(i))].end);
    EXPECT_LT(glm::length(end.pos_m - n.end.pos_m), 1e-4f) << "node " << i;
  });
  EXPECT_EQ(counted, t.num_nodes());
}

// Links are 16 bits: the cap is kMaxTreeNodes, and a tree grown to it keeps every link (the
// highest indices included) through a re-root.
TEST(MotionTree, TheLargestTreeKeepsEveryLink) {
  const auto& lib = default_library();
  const auto& arena = loaded_scene("arena");
  EXPECT_EQ(MotionTree(lib, arena.world, config_for(Strategy::kCommand, 1 << 20)).config().max_nodes, kMaxTreeNodes);
  MotionTreeConfig c = config_for(Strategy::kBreadthFirst, kMaxTreeNodes);
  c.max_depth = 255;
  MotionTree t(lib, arena.world, c);
  t.reset(walk_segment(lib), kOpen);
  ASSERT_NE(t.grow(GrowBudget::expansions(1000000)).status & kGrowOutOfNodes, 0);
  ASSERT_GT(t.num_nodes(), kMaxTreeNodes - 100);
  const auto links_hold = [&] {
    int counted = 0, highest = 0;
    t.for_each_node([&](int i, const MotionTreeNode& n) {
      ++counted;
      highest = std::max(highest, i);
      for (int k = n.first_child; k >= 0; k = t.node(k).next_sibling) EXPECT_EQ(t.node(k).parent, i);
    });
    EXPECT_EQ(counted, t.num_nodes());
    return highest;
  };
  EXPECT_GT(links_hold(), kMaxTreeNodes - 100) << "indices near the top of 16 bits are in use";
  const int child = t.select_child();
  ASSERT_GE(child, 0);
  t.advance_root(child);
  links_hold();
}

// ...and back down: a tree that grew large (a player alone on the server) and then holds a few
// hundred nodes (the server filled up) gives its chunks back at a re-root; the tree is the same
// tree after the move (nodes renumbered in their creation order, links kept), and grows on
// exactly as a tree that never moved its nodes would: the same choices, node for node.
void expect_cut_back_and_unchanged(const MotionLibrary& lib, const CollisionWorld& world) {
  const auto start = [&](MotionTreeConfig c) {
    auto tree = std::make_unique<MotionTree>(lib, world, c);
    tree->reset(walk_segment(lib), kOpen);
    tree->set_command(vec2(0.0f, 1.0f), kOpen);
    tree->grow(GrowBudget::expansions(6000));
    return tree;
  };
  // Caps neither tree reaches: the second replays the same calls, leaves every freed node where
  // it was and keeps every chunk.
  MotionTreeConfig keep = config_for(Strategy::kCommand, 16384);
  const std::unique_ptr<MotionTree> shrinking = start(keep);
  keep.compact_on_reroot = false;
  const std::unique_ptr<MotionTree> kept = start(keep);
  MotionTree &t = *shrinking, &u = *kept;
  const int full_capacity = t.node_capacity();
  ASSERT_GE(full_capacity, 2048) << "the tree filled a large pool first";
  const size_t full_bytes = t.node_bytes();
  int shrinks = 0;
  for (int step = 0; step < 80; ++step) {
    const int child_t = t.select_child(), child_u = u.select_child();
    ASSERT_EQ(child_t < 0, child_u < 0) << "step " << step;
    if (child_t < 0) {  // walked to a wall (a library of straight walks cannot turn away): stop
      EXPECT_GE(step, 24) << "walked far enough to shrink";
      break;
    }
    EXPECT_EQ(t.segment_of(child_t), u.segment_of(child_u)) << "step " << step;
    for (MotionTree* tree : {&t, &u}) {
      const int child = tree == &t ? child_t : child_u;
      const Placement at = tree->start_of(child);
      tree->advance_root(child);
      if (tree == &t) {
        EXPECT_EQ(t.node_capacity(), (t.num_nodes() + 63) / 64 * 64) << "no holes, no spare chunk";
      }
      tree->set_command(vec2(step % 10 < 5 ? 0.3f : -0.3f, 1.0f), at);
      tree->grow(GrowBudget::expansions(12));
    }
    if (t.node_capacity() < u.node_capacity()) ++shrinks;
    // Same tree, node for node, in the same walk order.
    const auto nt = snapshot(t), nu = snapshot(u);
    ASSERT_EQ(nt.size(), nu.size()) << "step " << step;
    for (size_t i = 0; i < nt.size(); ++i) {
      EXPECT_EQ(nt[i].transition, nu[i].transition) << "step " << step << ", node " << i;
      EXPECT_EQ(nt[i].end.pos_m, nu[i].end.pos_m) << "step " << step << ", node " << i;
      EXPECT_EQ(nt[i].end.heading_rad, nu[i].end.heading_rad) << "step " << step << ", node " << i;
      EXPECT_EQ(nt[i].match, nu[i].match) << "step " << step << ", node " << i;
      EXPECT_EQ(nt[i].grow_priority, nu[i].grow_priority) << "step " << step << ", node " << i;
      EXPECT_EQ(nt[i].depth, nu[i].depth) << "step " << step << ", node " << i;
      EXPECT_EQ(nt[i].expanded, nu[i].expanded) << "step " << step << ", node " << i;
    }
  }
  EXPECT_GT(shrinks, 0);
  EXPECT_GE(u.node_capacity(), full_capacity);
  EXPECT_LT(t.node_bytes(), full_bytes / 8) << "the pool was cut back";
  EXPECT_LE(t.node_capacity(), full_capacity / 8);
  EXPECT_GE(t.node_capacity(), t.num_nodes());
}

TEST(MotionTree, AnOversizedPoolIsCutBackAndTheTreeIsUnchanged) {
  const auto& lib = default_library();
  ASSERT_NO_FATAL_FAILURE(expect_cut_back_and_unchanged(lib, loaded_scene("arena").world));
  EXPECT_EQ(MotionTree(lib, loaded_scene("arena").world, config_for(Strategy::kCommand, 8192)).node_capacity(), 64)
      << "a new tree starts small";
}

// The same on capture the team did not make (the Bandai walk in inches under a dummy root, its
// own graph): the renumbering depends on no property of our library.
TEST(MotionTree, AnOversizedPoolOfAForeignCaptureIsCutBackAndTheTreeIsUnchanged) {
  FORESIGHT_REQUIRE_MOCAP();
  MotionLibrary lib;
  ASSERT_NO_FATAL_FAILURE(test::foreign_walk_library("", lib));
  ASSERT_NO_FATAL_FAILURE(expect_cut_back_and_unchanged(lib, loaded_scene("arena").world));
}

TEST(MotionTree, BudgetsCapsAndStatusesAreHonoured) {
  const auto& lib = default_library();
  const auto& arena = loaded_scene("arena");
  MotionTreeConfig small = config_for(Strategy::kCommand, 64);
  MotionTree t(lib, arena.world, small);
  t.reset(walk_segment(lib), kOpen);
  EXPECT_EQ(t.grow(GrowBudget::expansions(0)).expansions, 0);
  EXPECT_EQ(t.num_nodes(), 1);
  const GrowResult r = t.grow(GrowBudget::expansions(1000000));
  EXPECT_TRUE(r.status & kGrowOutOfNodes);
  EXPECT_LE(t.num_nodes(), 64);

  MotionTreeConfig shallow = config_for(Strategy::kBreadthFirst);
  shallow.max_depth = 2;
  MotionTree d(lib, arena.world, shallow);
  d.reset(walk_segment(lib), kOpen);
  const GrowResult rd = d.grow(GrowBudget::expansions(1000000));
  EXPECT_TRUE(rd.status & kGrowExhausted);
  EXPECT_EQ(d.max_depth_reached(), 2);

  // A deadline in the past spends nothing.
  MotionTree late(lib, arena.world, config_for(Strategy::kCommand));
  late.reset(walk_segment(lib), kOpen);
  const GrowResult rl = late.grow(GrowBudget::until(std::chrono::steady_clock::now()));
  EXPECT_TRUE(rl.status & kGrowBudgetSpent);
  EXPECT_EQ(rl.expansions, 0);
}

TEST(MotionTree, BreadthFirstFillsEachDepthBeforeTheNext) {
  const auto& lib = default_library();
  const auto& arena = loaded_scene("arena");
  MotionTree t(lib, arena.world, config_for(Strategy::kBreadthFirst, 100000));
  t.reset(walk_segment(lib), kOpen);
  t.grow(GrowBudget::expansions(1500));
  int shallowest_open = 1 << 30, deepest = 0;
  t.for_each_node([&](int, const MotionTreeNode& n) {
    if (!n.expanded) shallowest_open = std::min<int>(shallowest_open, n.depth);
    deepest = std::max<int>(deepest, n.depth);
  });
  // Every node shallower than the shallowest unexpanded one was expanded.
  EXPECT_LE(deepest, shallowest_open + 1);
}

// Mean end position of the tree's nodes along a direction, relative to the start.
float reach_along(const MotionTree& t, vec2 dir) {
  float sum = 0;
  int n = 0;
  t.for_each_node([&](int, const MotionTreeNode& node) {
    sum += glm::dot(node.end.pos_m - kOpen.pos_m, dir);
    ++n;
  });
  return sum / n;
}

TEST(MotionTree, CommandMatchingGrowsTowardsTheCommandAndSelectsIt) {
  const auto& lib = default_library();
  const auto& arena = loaded_scene("arena");
  for (Strategy s : {Strategy::kCommand, Strategy::kCommandNoResort, Strategy::kHybrid}) {
    for (float side : {1.0f, -1.0f}) {  // world +X is the avatar's left when facing +Z
      MotionTree t(lib, arena.world, config_for(s));
      t.reset(walk_segment(lib), kOpen);
      t.set_command(vec2(side, 0.0f), kOpen);
      t.grow(GrowBudget::expansions(1500));
      EXPECT_GT(reach_along(t, vec2(side, 0)), 0.3f) << strategy_name(s) << " side " << side;
      const int child = t.select_child();
      ASSERT_GE(child, 0);
      // The chosen branch turns the way the command points.
      const float turn = lib.segment_motion[t.segment_of(child)].end.heading_rad;
      EXPECT_GT(turn * side, 0.0f) << strategy_name(s) << " chose "
                                   << lib.graph.segments[t.segment_of(child)].name;
    }
  }
}

TEST(MotionTree, OnlyResortingStrategiesReorderWhenTheCommandChanges) {
  const auto& lib = default_library();
  const auto& arena = loaded_scene("arena");
  for (Strategy s : {Strategy::kCommand, Strategy::kCommandNoResort}) {
    MotionTree t(lib, arena.world, config_for(s));
    t.reset(walk_segment(lib), kOpen);
    t.set_command(vec2(1, 0), kOpen);
    t.grow(GrowBudget::expansions(400));
    std::vector<float> before;
    t.for_each_node([&](int, const MotionTreeNode& n) { before.push_back(n.grow_priority); });
    t.set_command(vec2(-1, 0), kOpen);
    t.grow(GrowBudget::expansions(0));  // priorities are brought up to date when the tree is next used
    std::vector<float> after;
    t.for_each_node([&](int, const MotionTreeNode& n) { after.push_back(n.grow_priority); });
    if (s == Strategy::kCommand)
      EXPECT_NE(before, after);
    else
      EXPECT_EQ(before, after);
  }
}

TEST(MotionTree, StatisticPrioritiesFollowTheLearnedChoices) {
  const auto& lib = default_library();
  const auto& arena = loaded_scene("arena");
  const int root = walk_segment(lib);
  // Pretend the training run always took the first successor of every segment.
  std::vector<int> taken;
  for (int s = 0; s < lib.graph.num_segments(); ++s)
    for (int k = 0; k < 20; ++k) taken.push_back(lib.graph.first_transition[s]);
  MotionTree t(lib, arena.world, config_for(Strategy::kStatistic));
  t.set_statistics(transition_statistics_learn(lib.graph, taken));
  t.reset(root, kOpen);
  t.grow(GrowBudget::expansions(800));
  // The favoured child's branch holds most of the tree.
  int favoured = -1, favoured_size = 0;
  for (int c = t.node(t.root()).first_child; c >= 0; c = t.node(c).next_sibling)
    if (t.node(c).transition == lib.graph.first_transition[root]) favoured = c;
  ASSERT_GE(favoured, 0);
  t.for_each_node([&](int i, const MotionTreeNode&) {
    for (int n = i; n >= 0; n = t.node(n).parent)
      if (n == favoured) {
        ++favoured_size;
        break;
      }
  });
  EXPECT_GT(favoured_size * 2, t.num_nodes());
}

// The branch sums are kept as nodes come and summed again only when matches or depths change:
// at every step of growing, re-commanding and advancing, the ranking is the one a fresh walk of
// the whole tree gives (paper 4.3: weights by depth below the root times each node's match).
TEST(MotionTree, KeptBranchSumsRankAsAFreshWalkOfTheTreeDoes) {
  const auto& lib = default_library();
  const auto& arena = loaded_scene("arena");
  MotionTree t(lib, arena.world, config_for(Strategy::kCommand));
  t.reset(walk_segment(lib), kOpen);
  const auto fresh_ranking = [&] {
    const auto& w = t.config().selection_weights;
    std::vector<std::pair<double, int>> sums;  // -sum, so that sorting puts the largest first
    for (int c = t.node(t.root()).first_child; c >= 0; c = t.node(c).next_sibling) {
      double sum = 0.0;
      std::vector<int> stack{c};
      while (!stack.empty()) {
        const MotionTreeNode& n = t.node(stack.back());
        stack.pop_back();
        sum += w[std::min<size_t>(n.depth - 1, w.size() - 1)] * static_cast<double>(n.match);
        for (int k = n.first_child; k >= 0; k = t.node(k).next_sibling) stack.push_back(k);
      }
      sums.emplace_back(-sum, c);
    }
    std::sort(sums.begin(), sums.end());
    std::vector<int> order;
    for (const auto& [sum, c] : sums) order.push_back(c);
    return order;
  };
  const vec2 commands[] = {{0, 1}, {1, 0}, {-1, 1}, {0, -1}};
  for (int step = 0; step < 24; ++step) {
    if (step % 6 == 0) t.set_command(commands[(step / 6) % 4], t.start_of(t.root()), false);
    t.grow(GrowBudget::expansions(40));
    const std::span<const int> kept = t.ranked_children();
    ASSERT_EQ(std::vector<int>(kept.begin(), kept.end()), fresh_ranking()) << "step " << step;
    if (step % 4 == 3 && !kept.empty()) t.advance_root(kept.front());
  }
  EXPECT_GT(t.num_nodes(), 50);
}

TEST(Strategy, NamesAndNumbersParseAndUnknownNamesDoNot) {
  EXPECT_EQ(strategy_from_name("breadth-first"), Strategy::kBreadthFirst);
  EXPECT_EQ(strategy_from_name("4"), Strategy::kHybrid);
  EXPECT_EQ(strategy_from_name("hybrid"), Strategy::kHybrid);
  EXPECT_FALSE(strategy_from_name("depth-first").has_value());
  EXPECT_FALSE(strategy_from_name("5").has_value());
  EXPECT_FALSE(strategy_from_name("").has_value());
  EXPECT_NE(strategy_names().find("command-no-resort"), std::string::npos);
}

}  // namespace
}  // namespace foresight

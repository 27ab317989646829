// Node storage shared by many trees (lookahead/motion_node_pool.hpp, issue 20 item 5): trees on
// one pool grow exactly as trees with their own, on one thread or several; the pool holds what
// the trees hold now (plus a bounded spare), not what each once held.
#include "lookahead/motion_tree.hpp"
#include "support/segments.hpp"

#include "library/foreign_capture.hpp"
#include "lookahead_fixture.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <thread>
#include <vector>

namespace foresight {
namespace {

using test::default_library;
using test::loaded_scene;
using test::walk_segment;

constexpr size_t kChunkBytes = sizeof(MotionNodePool::Chunk);

std::vector<MotionTreeNode> snapshot(const MotionTree& t) {
  std::vector<MotionTreeNode> out;
  t.for_each_node([&](int, const MotionTreeNode& n) { out.push_back(n); });
  return out;
}

// Avatar k of a small crowd: its own place and key in the arena's open middle.
Placement start_of(int k) { return {vec2(-3.0f + 1.5f * static_cast<float>(k), -4.0f), 0.0f}; }
vec2 key_of(int k, int step) {
  return step % 6 < 3 ? vec2(0.4f * static_cast<float>(k - 2), 1.0f) : vec2(-0.3f, 1.0f);
}

using Play = std::vector<std::vector<MotionTreeNode>>;  // the tree after every step

// A few seconds of one avatar's play: a large first growth (alone on the server), then re-roots
// with a tick's budget each.
Play play(MotionTree& t, const MotionLibrary& lib, int k) {
  Play trees;
  t.reset(walk_segment(lib), start_of(k));
  t.set_command(key_of(k, 0), start_of(k));
  t.grow(GrowBudget::expansions(3000));
  for (int step = 0; step < 30; ++step) {
    const int child = t.select_child();
    if (child < 0) break;
    const Placement at = t.start_of(child);
    t.advance_root(child);
    t.set_command(key_of(k, step), at);
    t.grow(GrowBudget::expansions(40));
    trees.push_back(snapshot(t));
  }
  return trees;
}

// Avatars 0..n-1 each played by a tree with its own pool.
std::vector<Play> play_alone(const MotionLibrary& lib, const CollisionWorld& world, int n) {
  std::vector<Play> plays;
  for (int k = 0; k < n; ++k) {
    MotionTree own(lib, world, MotionTreeConfig{});
    plays.push_back(play(own, lib, k));
  }
  return plays;
}

void expect_same_trees(const Play& a, const Play& b, int k) {
  ASSERT_EQ(a.size(), b.size()) << "avatar " << k;
  ASSERT_GE(a.size(), 10u) << "avatar " << k << " walked on";
  for (size_t step = 0; step < a.size(); ++step) {
    ASSERT_EQ(a[step].size(), b[step].size()) << "avatar " << k << ", step " << step;
    EXPECT_EQ(std::memcmp(a[step].data(), b[step].data(), a[step].size() * sizeof(MotionTreeNode)), 0)
        << "avatar " << k << ", step " << step;
  }
}

void expect_shared_pool_grows_trees_as_their_own(const MotionLibrary& lib) {
  const auto& arena = loaded_scene("arena");
  constexpr int kAvatars = 5;
  const std::vector<Play> alone = play_alone(lib, arena.world, kAvatars);
  MotionNodePool pool;
  {
    MotionTreeConfig shared;
    shared.node_pool = &pool;
    std::vector<std::unique_ptr<MotionTree>> trees;
    for (int k = 0; k < kAvatars; ++k) trees.push_back(std::make_unique<MotionTree>(lib, arena.world, shared));
    size_t held = 0;
    for (int k = 0; k < kAvatars; ++k) {
      ASSERT_NO_FATAL_FAILURE(expect_same_trees(play(*trees[static_cast<size_t>(k)], lib, k), alone[static_cast<size_t>(k)], k));
      held += static_cast<size_t>(trees[static_cast<size_t>(k)]->node_capacity()) / MotionNodePool::kChunkNodes;
    }
    EXPECT_EQ(pool.bytes_in_use(), held * kChunkBytes) << "the pool counts the chunks the trees hold";
    // After the first 3000 expansions each tree held ~2000 nodes; a tick's growth at each re-root
    // since leaves it with a few hundred, and the chunks it no longer needs went back.
    for (const auto& t : trees) {
      EXPECT_LT(t->node_capacity(), t->num_nodes() + 2 * MotionNodePool::kChunkNodes);
      EXPECT_LT(t->num_nodes(), 1000);
    }
  }
  EXPECT_EQ(pool.bytes_in_use(), 0u) << "trees give every chunk back when they go";
  EXPECT_GT(pool.bytes_spare(), 0u) << "some are kept for the next trees";
}

TEST(MotionNodePool, TreesSharingAPoolGrowAsTreesWithTheirOwnAndGiveEveryChunkBack) {
  ASSERT_NO_FATAL_FAILURE(expect_shared_pool_grows_trees_as_their_own(default_library()));
}

// The same on capture the team did not make (the Bandai walk in inches under a dummy root, its
// own graph).
TEST(MotionNodePool, TreesOfAForeignCaptureSharingAPoolGrowAsTreesWithTheirOwn) {
  FORESIGHT_REQUIRE_MOCAP();
  MotionLibrary lib;
  ASSERT_NO_FATAL_FAILURE(test::foreign_walk_library("", lib));
  ASSERT_NO_FATAL_FAILURE(expect_shared_pool_grows_trees_as_their_own(lib));
}

// The pool's lock is the only thing trees on the look-ahead workers share: trees grown on two
// threads at once are the trees grown one after another.
TEST(MotionNodePool, TreesOnTwoThreadsShareOnePool) {
  const auto& lib = default_library();
  const auto& arena = loaded_scene("arena");
  constexpr int kAvatars = 4;
  const std::vector<Play> alone = play_alone(lib, arena.world, kAvatars);
  std::vector<Play> threaded(kAvatars);
  MotionNodePool pool;
  MotionTreeConfig shared;
  shared.node_pool = &pool;
  {
    std::vector<std::thread> threads;
    for (int half = 0; half < 2; ++half)
      threads.emplace_back([&, half] {
        for (int k = half; k < kAvatars; k += 2) {
          MotionTree t(lib, arena.world, shared);
          threaded[static_cast<size_t>(k)] = play(t, lib, k);
        }
      });
    for (std::thread& t : threads) t.join();
  }
  for (int k = 0; k < kAvatars; ++k) expect_same_trees(threaded[static_cast<size_t>(k)], alone[static_cast<size_t>(k)], k);
  EXPECT_EQ(pool.bytes_in_use(), 0u);
}

// Spare chunks are bounded: a crowd of large trees that all shrink at once does not leave the
// pool holding their peak.
TEST(MotionNodePool, SpareChunksAreBounded) {
  const auto& lib = default_library();
  const auto& arena = loaded_scene("arena");
  MotionNodePool pool;
  MotionTreeConfig shared;
  shared.node_pool = &pool;
  std::vector<std::unique_ptr<MotionTree>> trees;
  for (int k = 0; k < 6; ++k) {
    trees.push_back(std::make_unique<MotionTree>(lib, arena.world, shared));
    trees.back()->reset(walk_segment(lib), start_of(k));
    trees.back()->set_command(vec2(0.0f, 1.0f), start_of(k));
    trees.back()->grow(GrowBudget::expansions(4000));
  }
  const size_t peak = pool.bytes_in_use();
  ASSERT_GT(peak, 6 * 20 * kChunkBytes) << "large trees first";
  for (const auto& t : trees) t->reset(walk_segment(lib), t->start_of(t->root()));  // keeps what it had filled
  for (const auto& t : trees) t->reset(walk_segment(lib), t->start_of(t->root()));  // now one node: one chunk
  EXPECT_EQ(pool.bytes_in_use(), 6 * kChunkBytes);
  EXPECT_LE(pool.bytes_spare(), 32 * kChunkBytes) << "at most the pool's minimum spare is kept";
  EXPECT_LT(pool.bytes_in_use() + pool.bytes_spare(), peak / 4);
}

}  // namespace
}  // namespace foresight

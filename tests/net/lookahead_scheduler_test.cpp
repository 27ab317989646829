// The look-ahead stage on its own (server/lookahead_scheduler.hpp): once warm, a tick's growth
// allocates nothing on the tick thread (the job handed to the workers fits std::function's inline
// storage; a capture too many put it on the heap every tick), and in expansion-budget mode the
// trees grown do not depend on how many workers grew them.
#include "library_build/library_source.hpp"
#include "lookahead_scheduler.hpp"
#include "support/alloc_counter.hpp"
#include "world/data_paths.hpp"

#include <gtest/gtest.h>

namespace foresight {
namespace {

TEST(LookaheadScheduler, AWarmTickAllocatesNothing) {
  const MotionLibrary lib = motion_library_default();
  Scene scene;
  CollisionWorld world;
  std::string error;
  ASSERT_TRUE(scene_world_load("arena", scene, world, error)) << error;
  server::ServerConfig config;
  config.expansions_per_avatar = 16;
  config.resort_interval_ticks = 1;  // the re-sort path every tick too
  server::LookaheadWorkers workers(1);
  server::LookaheadScheduler scheduler(config, lib, workers);
  MotionTreeConfig tree;
  tree.max_nodes = 256;
  server::HandleTable<server::GraphAvatar> avatars;
  for (uint32_t id = 1; id <= 4; ++id) {
    server::GraphAvatar g;
    g.id = id;
    g.avatar = std::make_unique<LookaheadAvatar>(lib, world, tree, find_spawn_segment(lib),
                                                 Placement{scene.spawns[0].pos_m + vec2(1.5f * static_cast<float>(id), 0.0f), 0.0f});
    g.input.camera_dir = {0.0f, 1.0f};
    avatars.add(std::move(g));
  }
  server::TickRecord record;
  uint32_t tick = 0;
  for (; tick < 40; ++tick) scheduler.grow(avatars.items(), tick, server::Clock::now(), record);  // pools at their cap
  EXPECT_EQ(record.expansions, 0) << "full trees grow no more";
  int allocations = 0;
  for (; tick < 50; ++tick) {
    test::AllocationCount counting;
    scheduler.grow(avatars.items(), tick, server::Clock::now(), record);
    allocations += counting.allocations();
  }
  EXPECT_EQ(allocations, 0);
  for (const server::GraphAvatar& g : avatars.items()) EXPECT_GE(g.avatar->tree().num_nodes(), 250) << "full";
}

// The room kept for advancing and sending follows their slow ticks, not their mean: with every
// fifth tick 10 ms slower the estimate is the slow ticks' (the mean was 2 ms short of them), and
// once they stop it comes back down.
TEST(LookaheadScheduler, TheTailEstimateCoversTheSlowTicksOfLate) {
  server::TailEstimate tail;
  EXPECT_EQ(tail.ms(), 0.0);
  for (int t = 0; t < 200; ++t) tail.note(t % 5 == 4 ? 20.0 : 10.0);
  EXPECT_NEAR(tail.ms(), 20.0, 1e-9);
  for (int t = 0; t < 64; ++t) tail.note(10.0);
  EXPECT_NEAR(tail.ms(), 10.0, 0.1) << "64 steady ticks later";
  // A steady tail is its own estimate.
  server::TailEstimate steady;
  for (int t = 0; t < 10; ++t) steady.note(7.0);
  EXPECT_NEAR(steady.ms(), 7.0, 1e-9);
}

TEST(LookaheadScheduler, InExpansionModeTheTreesDoNotDependOnTheWorkers) {
  const MotionLibrary lib = motion_library_default();
  Scene scene;
  CollisionWorld world;
  std::string error;
  ASSERT_TRUE(scene_world_load("arena", scene, world, error)) << error;
  server::ServerConfig config;
  config.expansions_per_avatar = 5;
  std::vector<int64_t> expansions;
  std::vector<std::vector<int>> sizes;
  for (const int threads : {1, 2}) {
    server::LookaheadWorkers workers(threads);
    server::LookaheadScheduler scheduler(config, lib, workers);
    server::HandleTable<server::GraphAvatar> avatars;
    for (uint32_t id = 1; id <= 5; ++id) {
      server::GraphAvatar g;
      g.id = id;
      g.avatar = std::make_unique<LookaheadAvatar>(lib, world, MotionTreeConfig{}, find_spawn_segment(lib),
                                                   Placement{scene.spawns[0].pos_m + vec2(1.5f * static_cast<float>(id), 0.0f), 0.0f});
      avatars.add(std::move(g));
    }
    server::TickRecord record;
    int64_t total = 0;
    for (uint32_t tick = 1; tick <= 3; ++tick) {
      scheduler.grow(avatars.items(), tick, server::Clock::now(), record);
      total += record.expansions;
    }
    expansions.push_back(total);
    sizes.emplace_back();
    for (const server::GraphAvatar& g : avatars.items()) sizes.back().push_back(g.avatar->tree().num_nodes());
    EXPECT_GT(record.tree_size_min, 1);
  }
  EXPECT_GT(expansions[0], 0);
  EXPECT_EQ(expansions[0], expansions[1]);
  EXPECT_EQ(sizes[0], sizes[1]);
  server::LookaheadWorkers workers(1);
  server::LookaheadScheduler scheduler(config, lib, workers);
  server::TickRecord none;
  scheduler.grow({}, 1, server::Clock::now(), none);
  EXPECT_EQ(none.tree_size_min, -1) << "no avatars: not part of the tree figures";
}

}  // namespace
}  // namespace foresight

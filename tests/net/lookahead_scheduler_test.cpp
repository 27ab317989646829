// The look-ahead stage on its own (server/lookahead_scheduler.hpp): once warm, a tick's growth
// allocates nothing on the tick thread (the job handed to the workers fits std::function's inline
// storage; a capture too many put it on the heap every tick), and in expansion-budget mode the
// trees grown do not depend on how many workers grew them.
#include "lookahead/lookahead_fixture.hpp"
#include "lookahead_scheduler.hpp"
#include "support/alloc_counter.hpp"

#include <gtest/gtest.h>

namespace foresight {
namespace {

TEST(LookaheadScheduler, AWarmTickAllocatesNothing) {
  const MotionLibrary& lib = test::default_library();
  const Scene& scene = test::loaded_scene("arena").scene;
  const CollisionWorld& world = test::loaded_scene("arena").world;
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

// The growth is the tick's last stage and takes what the tick leaves: the period less what the
// stages before it took and the margin, at most the cap. A tick whose earlier stages ran slow
// (here: began 28 of its 33.3 ms ago, with a 6 ms margin) grows nothing and re-sorts nothing.
TEST(LookaheadScheduler, TheGrowthTakesWhatTheTickLeavesAndNoMore) {
  const MotionLibrary& lib = test::default_library();
  const Scene& scene = test::loaded_scene("arena").scene;
  const CollisionWorld& world = test::loaded_scene("arena").world;
  server::ServerConfig config;  // timed: 30 Hz, at most 8 ms, 6 ms margin
  ASSERT_EQ(config.expansions_per_avatar, 0);
  config.tick_hz = 30;
  config.lookahead_budget_ms = 8.0;
  config.tick_safety_margin_ms = 6.0;
  config.resort_interval_ticks = 1;
  server::LookaheadWorkers workers(1);
  server::LookaheadScheduler scheduler(config, lib, workers);
  server::HandleTable<server::GraphAvatar> avatars;
  server::GraphAvatar g;
  g.id = 1;
  g.avatar = std::make_unique<LookaheadAvatar>(lib, world, MotionTreeConfig{}, find_spawn_segment(lib),
                                               Placement{scene.spawns[0].pos_m, 0.0f});
  g.input.camera_dir = {0.0f, 1.0f};
  avatars.add(std::move(g));
  scheduler.take_inputs(avatars.items());
  const auto ago = [](double ms) {
    return server::Clock::now() - std::chrono::duration_cast<server::Clock::duration>(std::chrono::duration<double, std::milli>(ms));
  };
  server::TickRecord late;
  scheduler.grow(avatars.items(), 1, ago(28.0), late);
  EXPECT_EQ(late.budget_ms, 0.0f);
  EXPECT_EQ(late.expansions, 0);
  EXPECT_EQ(avatars.items()[0].avatar->tree().num_nodes(), 1) << "only the root";
  server::TickRecord early;
  scheduler.grow(avatars.items(), 2, ago(5.0), early);
  EXPECT_LE(early.budget_ms, 8.0f) << "the cap";
  EXPECT_GT(early.budget_ms, 0.0f);
  EXPECT_GT(early.expansions, 0);
  EXPECT_GT(avatars.items()[0].avatar->tree().num_nodes(), 1);
}

TEST(LookaheadScheduler, InExpansionModeTheTreesDoNotDependOnTheWorkers) {
  const MotionLibrary& lib = test::default_library();
  const Scene& scene = test::loaded_scene("arena").scene;
  const CollisionWorld& world = test::loaded_scene("arena").world;
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

// Replaying recordings: the shipped ones reach their goals without collisions, deterministically;
// no budget is safe; every strategy replays without collisions; the generator's run is reproduced
// exactly by replaying what it recorded.
#include "scripted/recording_generator.hpp"
#include "scripted/replay.hpp"
#include "lookahead_fixture.hpp"

#include <gtest/gtest.h>

namespace foresight {
namespace {

using test::default_library;
using test::loaded_scene;

const Recording& shipped(const std::string& name) {
  static std::map<std::string, Recording> cache;
  auto it = cache.find(name);
  if (it == cache.end()) {
    Recording r;
    std::string error;
    if (!recording_load(data_dir() / "recordings" / (name + ".json"), r, error)) ADD_FAILURE() << error;
    it = cache.emplace(name, std::move(r)).first;
  }
  return it->second;
}

const CollisionWorld& world_of(const Recording& r) { return loaded_scene(r.scene).world; }

TEST(Replay, ShippedRecordingsReachTheirGoalsWithoutCollisions) {
  // Slow builds replay the training recordings only (the sanitizer run stays short).
  const auto& lib = default_library();
  const std::vector<std::string> names =
      test::kSlowBuild ? std::vector<std::string>{"maze_train", "obstacles_train", "pillars_train"}
                       : std::vector<std::string>{"maze_train",     "maze_eval",     "obstacles_train", "obstacles_eval",
                                                  "doorways_train", "doorways_eval", "beams_train",     "beams_eval",
                                                  "pillars_train",  "pillars_eval",  "dead_end_train",  "dead_end_eval"};
  for (const std::string& name : names) {
    SCOPED_TRACE(name);
    const Recording& rec = shipped(name);
    // Open-loop commands steer a different avatar when the library changes: then the recordings
    // must be regenerated (docs/RECORDINGS.md).
    EXPECT_EQ(rec.library_hash, lib.content_hash)
        << "recorded with another motion library: regenerate data/recordings with foresight-record";
    const ReplayResult r = replay_recording(lib, world_of(rec), rec, ReplayConfig{});
    ASSERT_TRUE(r.error.empty()) << r.error;
    EXPECT_TRUE(r.reached_goal);
    EXPECT_EQ(r.colliding_frames, 0);
    EXPECT_LE(r.time_to_goal_s, rec.duration_s() + ReplayConfig{}.grace_after_end_s);  // may coast in after the keys
    EXPECT_GT(r.avg_tree_size, 10.0);
    EXPECT_FALSE(r.transitions_taken.empty());
    EXPECT_FALSE(r.responses.empty());
    EXPECT_GT(r.mean_command_angle_deg, 0.0);
    EXPECT_LT(r.mean_command_angle_deg, 90.0);
    ASSERT_FALSE(r.path.empty());
    EXPECT_LT(glm::length(r.path.front() - rec.start_pos_m), 1e-4f);
    EXPECT_LE(glm::length(r.path.back() - rec.goal_pos_m), rec.goal_radius_m);
    if (rec.scene == "obstacles") {
      // Its route passes under the beam: the avatar crouched without being told (crouch is
      // never pressed in the recordings).
      bool crouched = false;
      for (int t : r.transitions_taken)
        crouched |= (lib.graph.segments[lib.graph.transitions[t].to].tags & kTagCrouch) != 0;
      EXPECT_TRUE(crouched);
    }
  }
}

// A key held against a wall is a stall (no 0.3 m of progress in 3 s), counted once per 3 s; a
// player who holds nothing is not stalled.
TEST(Replay, AKeyHeldIntoAWallCountsAsStallsAndStandingStillDoesNot) {
  const auto& lib = default_library();
  const auto& maze = loaded_scene("maze");
  const SpawnPoint& spawn = maze.scene.spawns.front();
  ReplayConfig config;
  config.max_seconds = 20;
  config.stop_at_goal = false;
  const auto run_holding = [&](vec2 camera_dir) {
    ReplayRun run(lib, maze.world, Placement{spawn.pos_m, spawn.heading_rad}, vec2(100.0f), 0.5f, config);
    EXPECT_TRUE(run.ok()) << run.error();
    ControlInput in;
    in.camera_dir = camera_dir;
    in.camera_yaw_rad = spawn.heading_rad;  // the camera behind the avatar: "forward" is its facing
    while (!run.done()) run.frame(in);
    return run.finish();
  };
  // Backwards from the spawn is the maze's outer wall, 1 m behind it: the avatar turns to it and
  // then can go nowhere for most of the 20 s.
  const ReplayResult into_wall = run_holding(vec2(0.0f, -1.0f));
  EXPECT_GE(into_wall.stalls, 3) << "about 15 s held against the wall";
  EXPECT_LE(into_wall.stalls, 6);
  EXPECT_EQ(run_holding(vec2(0.0f)).stalls, 0);
}

TEST(Replay, IsDeterministicWithAnExpansionBudget) {
  const Recording& rec = shipped("maze_train");
  ReplayConfig config;
  config.max_seconds = test::kSlowBuild ? 10.0 : 40.0;
  const ReplayResult a = replay_recording(default_library(), world_of(rec), rec, config);
  const ReplayResult b = replay_recording(default_library(), world_of(rec), rec, config);
  ASSERT_FALSE(a.path.empty());
  EXPECT_EQ(a.path, b.path);
  EXPECT_EQ(a.transitions_taken, b.transitions_taken);
  EXPECT_EQ(a.avg_tree_size, b.avg_tree_size);
  EXPECT_EQ(a.responses, b.responses);
}

TEST(Replay, WithNoBudgetTheAvatarHoldsAndNeverCollides) {
  const Recording& rec = shipped("obstacles_train");
  ReplayConfig config;
  config.expansions_per_frame = 0;
  config.max_seconds = test::kSlowBuild ? 3.0 : 20.0;
  const ReplayResult r = replay_recording(default_library(), world_of(rec), rec, config);
  ASSERT_TRUE(r.error.empty()) << r.error;
  EXPECT_FALSE(r.reached_goal);
  EXPECT_EQ(r.colliding_frames, 0);
  EXPECT_GT(r.fallbacks, 0);
  for (const vec2& p : r.path) EXPECT_LT(glm::length(p - rec.start_pos_m), 0.2f);  // idles in place
}

TEST(Replay, EveryStrategyReplaysWithoutCollisions) {
  const auto& lib = default_library();
  const Recording& train = shipped("maze_train");
  const Recording& eval = shipped("maze_eval");
  ReplayConfig config;
  config.max_seconds = test::kSlowBuild ? 6.0 : 30.0;
  config.statistics = learn_statistics(lib, world_of(train), train, config);
  ASSERT_EQ(config.statistics.probability.size(), lib.graph.transitions.size());
  for (int s = 0; s < kNumStrategies; ++s) {
    SCOPED_TRACE(strategy_name(static_cast<Strategy>(s)));
    config.tree.strategy = static_cast<Strategy>(s);
    const ReplayResult r = replay_recording(lib, world_of(eval), eval, config);
    ASSERT_TRUE(r.error.empty()) << r.error;
    EXPECT_EQ(r.colliding_frames, 0);
    EXPECT_GT(r.avg_tree_size, 1.0);
    EXPECT_GT(r.seconds, 0.0);
  }
}

TEST(Replay, LearnedStatisticsFavourTheTransitionsTaken) {
  const auto& lib = default_library();
  const Recording& train = shipped("maze_train");
  ReplayConfig config;
  config.max_seconds = test::kSlowBuild ? 3.0 : 30.0;
  config.tree.strategy = Strategy::kBreadthFirst;  // learn_statistics uses kCommand whatever this says
  const TransitionStatistics stats = learn_statistics(lib, world_of(train), train, config);
  config.tree.strategy = Strategy::kCommand;
  const ReplayResult r = replay_recording(lib, world_of(train), train, config);
  ASSERT_FALSE(r.transitions_taken.empty());
  EXPECT_EQ(stats.probability, transition_statistics_learn(lib.graph, r.transitions_taken).probability);
}

TEST(Replay, TheGeneratorsRunIsReproducedByReplayingItsRecording) {
  const auto& lib = default_library();
  const auto& obstacles = loaded_scene("obstacles");
  RecordingGeneratorConfig config;
  config.scene = "obstacles";
  config.seed = 3;
  config.replay.max_seconds = test::kSlowBuild ? 8.0 : 25.0;
  GeneratedRecording g;
  std::string error;
  ASSERT_TRUE(recording_generate(lib, obstacles.scene, obstacles.world, config, g, error)) << error;
  Recording parsed;
  ASSERT_TRUE(recording_parse(recording_write(g.recording), "g.json", parsed, error)) << error;
  ReplayConfig rc = config.replay;
  rc.grace_after_end_s = -1;  // as long as the generator ran
  const ReplayResult r = replay_recording(lib, obstacles.world, parsed, rc);
  ASSERT_GE(r.path.size(), g.run.path.size());
  EXPECT_EQ(std::vector<vec2>(r.path.begin(), r.path.begin() + static_cast<long>(g.run.path.size())), g.run.path);
  EXPECT_EQ(r.colliding_frames, 0);
}

TEST(Replay, ClipTimeFollowsDisplayTime) {
  const Recording& rec = shipped("maze_train");
  ReplayConfig at30, at15;
  at30.max_seconds = at15.max_seconds = test::kSlowBuild ? 2.0 : 8.0;
  at15.frame_interval_s = 1.0 / 15.0;
  at15.expansions_per_frame = 2 * at30.expansions_per_frame;
  const ReplayResult a = replay_recording(default_library(), world_of(rec), rec, at30);
  const ReplayResult b = replay_recording(default_library(), world_of(rec), rec, at15);
  // Same simulated time, half the display frames.
  EXPECT_NEAR(a.seconds, b.seconds, 0.07);
  EXPECT_NEAR(static_cast<double>(a.path.size()), 2.0 * static_cast<double>(b.path.size()), 2.0);
  EXPECT_EQ(a.colliding_frames + b.colliding_frames, 0);
}

TEST(Replay, RefusesToStartWhereItCannot) {
  const auto& lib = default_library();
  Recording rec = shipped("maze_train");
  rec.start_pos_m = vec2(0.0f, 5.0f);  // inside the west wall
  ReplayResult r = replay_recording(lib, world_of(rec), rec, ReplayConfig{});
  EXPECT_NE(r.error.find("is not free"), std::string::npos) << r.error;
  EXPECT_TRUE(r.path.empty());

  ReplayConfig config;
  config.statistics.probability = {0.5f};  // learned for another library
  r = replay_recording(lib, world_of(shipped("maze_train")), shipped("maze_train"), config);
  EXPECT_NE(r.error.find("another library"), std::string::npos) << r.error;
  EXPECT_TRUE(learn_statistics(lib, world_of(rec), rec, ReplayConfig{}).empty());
}

}  // namespace
}  // namespace foresight

// Real bots (BotFleet: ClientConnection, scripts, collision watch) against a real server, both
// in this process over loopback UDP and driven by one fake clock (bot_match.hpp).
#include "bot_match.hpp"
#include "support/test_paths.hpp"

#include <gtest/gtest.h>

#include <thread>

namespace foresight {
namespace {

using namespace std::chrono_literals;

server::ServerConfig match_config(const std::string& scene, const std::filesystem::path& motions) {
  server::ServerConfig c = test::test_server_config(scene);
  c.motions.motions_dir = motions;
  return c;
}

struct Match : test::BotMatch {
  Match(const std::string& scene, int bots, bots::BotScript script, const std::filesystem::path& motions = {})
      : BotMatch(match_config(scene, motions), bots, script) {}
};

TEST(Bots, GoalSeekersConnectWalkAndNeverCollide) {
  Match m("arena", 6, bots::BotScript::kGoals);
  bots::BotFleet fleet(m.server.library(), m.config);
  ASSERT_TRUE(fleet.ok()) << fleet.error();
  m.play(fleet, 30 * 40);  // 40 s
  fleet.request_stats();
  m.play(fleet, 5);
  ASSERT_TRUE(fleet.stats_arrived());
  const bots::BotReport r = fleet.report(m.now);
  fleet.disconnect_all();

  EXPECT_TRUE(r.error.empty()) << r.error;
  EXPECT_EQ(r.connected, 6);
  EXPECT_EQ(r.connected_at_end, 6);
  EXPECT_EQ(r.scene, "arena");
  EXPECT_GT(r.walked_m_mean, 10.0) << "the scripted players should move their avatars";
  EXPECT_GT(r.goals_reached, 0u);
  EXPECT_EQ(r.scene_collisions, 0u);
  EXPECT_EQ(r.avatar_contacts, 0u);
  EXPECT_EQ(r.invalid_states, 0u);
  EXPECT_GT(r.avatars_checked, 6u * 20 * 30);
  EXPECT_EQ(r.drops.total(), 0u);
  EXPECT_GT(r.rtt_ms.count(), 100u);
  EXPECT_GT(r.snapshot_interval_ms.count(), 100u);
  EXPECT_GT(r.down_kbps_p50, 0.0);
  ASSERT_TRUE(r.has_server_stats);
  EXPECT_EQ(r.server.players, 6u);
  EXPECT_EQ(r.server.avatar_contacts, 0u);
  EXPECT_GT(m.server.counters().steered_frames, 0u) << "steering mode is on by default";

  const nlohmann::json j = bots::bot_report_json(r);
  for (const char* key : {"bots", "connected", "refused", "goals_reached", "collisions", "rtt_ms_p50",
                          "rtt_ms_p99", "snapshot_interval_ms_p99", "down_kbps_per_client_p50",
                          "server_tick_ms_p99", "server_overruns", "tree_size_mean", "packets_dropped"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["bots"], 6);
  EXPECT_FALSE(j["server_tick_ms_p99"].is_null());
}

// Steering mode on the server (the default, --steer-deg-per-s 540): avatars turn their playing
// motion, each turn is reserved at once, so bodies still never meet, and the clients' shown
// poses stay out of the scene. Eight goal seekers in the maze's corridors.
TEST(Bots, SteeredGoalSeekersNeverCollideOrTouch) {
  server::ServerConfig config = match_config("maze", {});
  ASSERT_FLOAT_EQ(config.steer_deg_per_s, 540.0f);
  test::BotMatch m(config, 8, bots::BotScript::kGoals);
  bots::BotFleet fleet(m.server.library(), m.config);
  ASSERT_TRUE(fleet.ok()) << fleet.error();
  m.play(fleet, 30 * 40);  // 40 s
  const bots::BotReport r = fleet.report(m.now);
  fleet.disconnect_all();
  EXPECT_TRUE(r.error.empty()) << r.error;
  EXPECT_EQ(r.connected, 8);
  EXPECT_GT(r.walked_m_mean, 10.0);
  EXPECT_GT(r.goals_reached, 0u);
  EXPECT_EQ(r.scene_collisions, 0u);
  EXPECT_EQ(r.avatar_contacts, 0u);
  EXPECT_EQ(r.invalid_states, 0u);
  EXPECT_EQ(m.server.counters().avatar_contacts, 0u);
  EXPECT_GT(m.server.counters().steered_frames, 100u) << "the avatars should have been steered";
}

TEST(Bots, AGoalSeekerReachesTheGoalInTheMazeAndTheObstacleCourseCrouchingWhereNeeded) {
  for (const char* scene : {"maze", "obstacles"}) {
    Match m(scene, 1, bots::BotScript::kGoals);
    bots::BotFleet fleet(m.server.library(), m.config);
    ASSERT_TRUE(fleet.ok()) << fleet.error();
    bool crouched = false;
    uint64_t goals = 0;
    int frame = 0;
    for (; frame < 30 * 120 && goals == 0; ++frame) {  // up to 2 minutes
      m.play(fleet, 1);
      for (uint32_t id : m.server.avatar_ids()) {
        const int segment = m.server.avatar(id)->playback().segment;
        crouched |= (m.server.library().graph.segments[static_cast<size_t>(segment)].tags & kTagCrouch) != 0;
      }
      goals = fleet.report(m.now).goals_reached;
    }
    const bots::BotReport r = fleet.report(m.now);
    EXPECT_GE(r.goals_reached, 1u) << scene;
    EXPECT_EQ(r.scene_collisions + r.avatar_contacts, 0u) << scene;
    // The obstacle course has a beam only a crouching body passes: the bot never presses crouch,
    // the look-ahead finds the crouched motions by itself.
    if (std::string(scene) == "obstacles") {
      EXPECT_TRUE(crouched);
    }
    std::printf("[          ] %s: first goal after %.1f s%s\n", scene, frame / 30.0,
                crouched ? ", crouched on the way" : "");
    fleet.disconnect_all();
  }
}

TEST(Bots, WanderersAndReplayersMove) {
  for (bots::BotScript script : {bots::BotScript::kWander, bots::BotScript::kReplay}) {
    Match m("maze", 3, script);
    bots::BotFleet fleet(m.server.library(), m.config);
    m.play(fleet, 30 * 15);
    const bots::BotReport r = fleet.report(m.now);
    EXPECT_TRUE(r.error.empty()) << r.error;
    EXPECT_EQ(r.connected, 3) << r.script;
    EXPECT_GT(r.walked_m_mean, 3.0) << r.script;
    EXPECT_EQ(r.scene_collisions, 0u) << r.script;
    EXPECT_EQ(r.avatar_contacts, 0u) << r.script;
  }
}

// The same script for both libraries: 8 goal-seeking bots on the maze for 40 s, once on the
// built-in library and once on the Bandai capture (docs/CAPTURED_MOTION.md). Captured motion must
// carry the avatars at least half as far, reach goals, never collide, and give the look-ahead
// trees of the same order.
bots::BotReport goal_bots_on_the_maze(const std::filesystem::path& motions) {
  server::ServerConfig config = match_config("maze", motions);
  // A fixed count keeps the test deterministic (a real server's time budget gives 8 players here
  // trees at the 8192-node cap); 400 over 40 s keeps it near a minute in the ASan build.
  config.expansions_per_avatar = 400;
  test::BotMatch m(config, 8, bots::BotScript::kGoals);
  // The bots load the same library themselves (what --motions DIR does on both sides).
  MotionLibrary library;
  std::string error;
  MotionSource source;
  source.motions_dir = motions;
  EXPECT_TRUE(motion_library_load(source, library, error)) << error;
  EXPECT_EQ(library.content_hash, m.server.library().content_hash);
  bots::BotFleet fleet(library, m.config);
  m.play(fleet, 30 * 40);
  fleet.request_stats();
  m.play(fleet, 5);
  EXPECT_TRUE(fleet.stats_arrived());
  const bots::BotReport r = fleet.report(m.now);
  fleet.disconnect_all();
  EXPECT_TRUE(r.error.empty()) << r.error;
  EXPECT_EQ(r.connected, 8);
  EXPECT_EQ(r.scene_collisions + r.avatar_contacts, 0u);
  EXPECT_EQ(r.invalid_states, 0u);
  std::printf("[          ] %s: walked %.1f m per bot, %llu goals, tree %.0f nodes\n",
              motions.empty() ? "built-in" : "captured", r.walked_m_mean,
              static_cast<unsigned long long>(r.goals_reached), r.server.tree_size_mean);
  return r;
}

TEST(Bots, GoalSeekersOnRealMotionCaptureWalkHalfAsFarAsOnTheBuiltInLibraryAtLeast) {
  FORESIGHT_REQUIRE_MOCAP();
  const bots::BotReport built_in = goal_bots_on_the_maze({});
  const bots::BotReport captured = goal_bots_on_the_maze(test::mocap_dir() / "locomotion");
  EXPECT_GE(captured.walked_m_mean, 0.5 * built_in.walked_m_mean);
  EXPECT_GT(captured.goals_reached, 0u);
  ASSERT_TRUE(captured.has_server_stats);
  EXPECT_GE(captured.server.tree_size_mean, 1000.0);
}

// The arena on captured motion only: the avatars' locomotion and the fighters' extra strikes both
// from the Bandai capture. The fighters approach dodging bots, strike and hit.
TEST(Bots, FightersOnCapturedLocomotionAndStrikesStrikeAndHit) {
  FORESIGHT_REQUIRE_MOCAP();
  server::ServerConfig config = match_config("arena", test::mocap_dir() / "locomotion");
  config.fighters = -1;  // one per NPC spawn of the arena
  config.fighter_strikes = (test::mocap_dir() / "fighting").string();
  config.fighter_strikes_sidecar = std::string(FORESIGHT_DATA_DIR) + "/fighter/bandai_fighting.strikes.json";
  test::BotMatch m(config, 6, bots::BotScript::kDodge);
  ASSERT_NE(m.server.fighter_assets(), nullptr);
  bots::BotFleet fleet(m.server.library(), m.config);
  m.play(fleet, 30 * 30);
  const bots::BotReport r = fleet.report(m.now);
  fleet.disconnect_all();
  EXPECT_EQ(r.connected, 6);
  const server::ServerCounters& c = m.server.counters();
  std::printf("[          ] captured arena: %llu strikes, %llu hits in 30 s\n",
              static_cast<unsigned long long>(c.fighter_strikes), static_cast<unsigned long long>(c.fighter_hits));
  EXPECT_GE(c.fighter_strikes, 3u);
  EXPECT_GE(c.fighter_hits, 1u);
  EXPECT_EQ(c.fighter_strike_failures, 0u);
  EXPECT_EQ(r.scene_collisions, 0u);
}

TEST(Bots, AnotherLibraryIsRefusedAndReported) {
  Match m("maze", 3, bots::BotScript::kGoals);
  MotionLibrary other = m.server.library();
  other.content_hash ^= 1;  // what a different --motions folder would give
  bots::BotFleet fleet(other, m.config);
  m.play(fleet, 10);
  EXPECT_TRUE(fleet.all_finished());
  const bots::BotReport r = fleet.report(m.now);
  EXPECT_EQ(r.connected, 0);
  EXPECT_EQ(r.refused, 3);
  ASSERT_EQ(r.refusals.size(), 1u) << "one distinct message, not one per bot";
  EXPECT_NE(r.refusals[0].find("Library"), std::string::npos) << r.refusals[0];
  EXPECT_EQ(m.server.num_players(), 0);
}

TEST(Bots, DisconnectEndsTheSessionsAtOnce) {
  Match m("maze", 4, bots::BotScript::kGoals);
  bots::BotFleet fleet(m.server.library(), m.config);
  m.play(fleet, 30);
  ASSERT_EQ(m.server.num_players(), 4);
  fleet.disconnect_all();
  m.play(fleet, 2);
  EXPECT_EQ(m.server.num_players(), 0);
}

TEST(Bots, RealTimeRunAgainstAServerThread) {
  // The path foresight-bots takes: bot_fleet_run's frame loop, epoll between frames, the stats
  // request and the disconnect at the end, against a server ticking in real time.
  Match m("maze", 4, bots::BotScript::kGoals);
  m.config.seconds = 2.0;
  std::thread server_thread([&] { m.server.run(); });
  const bots::BotReport r = bots::bot_fleet_run(m.server.library(), m.config, nullptr);
  std::this_thread::sleep_for(300ms);  // a few ticks to read the Disconnects
  m.server.stop();
  server_thread.join();
  EXPECT_TRUE(r.error.empty()) << r.error;
  EXPECT_EQ(r.connected, 4);
  EXPECT_GT(r.rtt_ms.count(), 20u);
  EXPECT_LT(r.rtt_ms.percentile(0.5), 200.0);
  EXPECT_GT(r.snapshot_interval_ms.count(), 20u);
  EXPECT_TRUE(r.has_server_stats);
  EXPECT_EQ(r.scene_collisions + r.avatar_contacts, 0u);
  EXPECT_EQ(m.server.num_players(), 0) << "bot_fleet_run disconnects at the end";
}

}  // namespace
}  // namespace foresight

// Bots walk the terrain scene (issue 7): a real server in terrain locomotion and real bots over
// loopback UDP, one fake clock. The avatars move by the footstep and upper-body planners, the
// snapshots carry their bodies (TerrainBody), the bots' watch checks every body against the scene.
#include "bot_match.hpp"
#include "support/test_paths.hpp"

#include <gtest/gtest.h>

namespace foresight {
namespace {

using namespace std::chrono_literals;

server::ServerConfig terrain_config(server::Locomotion locomotion) {
  server::ServerConfig c = test::test_server_config("terrain");
  c.locomotion = locomotion;
  return c;
}

struct TerrainMatch : test::BotMatch {
  explicit TerrainMatch(int bots, server::Locomotion locomotion = server::Locomotion::kAuto)
      : BotMatch(terrain_config(locomotion), bots, bots::BotScript::kGoals, 3) {}
};

TEST(TerrainBots, GoalSeekersWalkTheTerrainSceneByTheFootstepPlanner) {
  TerrainMatch m(4);
  ASSERT_TRUE(m.server.terrain_mode()) << "the terrain scene has a height field: auto picks terrain";
  EXPECT_EQ(m.server.num_fighters(), 0);
  bots::BotFleet fleet(m.server.library(), m.config);
  ASSERT_TRUE(fleet.ok()) << fleet.error();
  m.play(fleet, 30 * 40);  // 40 s
  for (uint32_t id : m.server.avatar_ids()) {
    const terrain::TerrainAvatar* a = m.server.terrain_avatar(id);
    ASSERT_NE(a, nullptr);
    EXPECT_EQ(m.server.avatar(id), nullptr) << "no motion tree on terrain";
    EXPECT_GT(a->steps, 5) << "avatar " << id;
    std::printf("[          ] avatar %u: %d steps, %d turns on the spot, %d refusals (last: %s%s) at (%.2f, %.2f)\n", id,
                a->steps, a->pivots, a->refusals, terrain::terrain_step_status_name(a->last_status),
                a->vetoed ? ", vetoed" : "", a->body.pelvis_m.x, a->body.pelvis_m.z);
  }
  const bots::BotReport r = fleet.report(m.now);
  fleet.disconnect_all();
  EXPECT_EQ(r.connected_at_end, 4);
  EXPECT_GT(r.walked_m_mean, 8.0);
  EXPECT_GT(r.goals_reached, 0u);
  EXPECT_EQ(r.invalid_states, 0u) << "terrain avatars' states are not library playbacks, and not rejected";
  EXPECT_EQ(r.scene_collisions, 0u);
  EXPECT_EQ(r.avatar_contacts, 0u);
  EXPECT_EQ(m.server.counters().avatar_contacts, 0u);
  EXPECT_GT(m.server.counters().terrain_steps, 40u);
  EXPECT_GT(r.avatars_checked, 4u * 20 * 20);
  EXPECT_GT(m.server.tick_stats().mean().terrain_ms, 0.0f);
}

TEST(TerrainBots, SnapshotsCarryEveryTerrainBodyWithItsAvatar) {
  TerrainMatch m(3);
  bots::BotFleet fleet(m.server.library(), m.config);
  ASSERT_TRUE(fleet.ok()) << fleet.error();
  m.play(fleet, 30 * 4);
  // Each bot's view of the newest tick: three terrain avatars, each with its body, whose pelvis
  // is where the server has it (1 mm quantisation; a tick behind at most).
  for (int i = 0; i < 3; ++i) {
    const protocol::ClientConnection& c = fleet.connection(i);
    ASSERT_TRUE(c.has_snapshot());
    ASSERT_EQ(c.avatars().size(), 3u);
    ASSERT_EQ(c.terrain_bodies().size(), 3u);
    for (const wire::AvatarState& s : c.avatars()) {
      EXPECT_TRUE(s.flags() & protocol::kAvatarTerrain);
      EXPECT_EQ(s.segment(), protocol::kNoSegment);
      const auto body = std::find_if(c.terrain_bodies().begin(), c.terrain_bodies().end(),
                                     [&](const protocol::TerrainBodyState& b) { return b.avatar == s.id(); });
      ASSERT_NE(body, c.terrain_bodies().end());
      const terrain::TerrainAvatar* a = m.server.terrain_avatar(s.id());
      ASSERT_NE(a, nullptr);
      EXPECT_LT(glm::length(body->pelvis_m - a->body.pelvis_m), 0.1f);
      EXPECT_GT(body->pelvis_m.y, 0.7f);
    }
  }
  fleet.disconnect_all();
}

TEST(TerrainServer, ARawClientSteersItsTerrainAvatarInCameraSpaceAndGetsNoTree) {
  server::Server server;
  std::string error;
  ASSERT_TRUE(server.start(test::test_server_config("terrain"), error)) << error;
  server::Clock::time_point now = server::Clock::now();
  test::RawClient c(server.port());
  ASSERT_TRUE(c.connect(server, now, server.library().content_hash));
  const terrain::TerrainAvatar* a = server.terrain_avatar(c.avatar);
  ASSERT_NE(a, nullptr);
  const vec2 start = terrain::terrain_avatar_ground(*a);
  // The camera looks along +X (yaw 90 degrees): "forward" on screen is +X in the world.
  uint32_t seq = 1;
  for (int i = 0; i < 90; ++i) {
    c.send_input(vec2(0.0f, 1.0f), seq++, kPi / 2);
    server.run_tick(now += 33ms);
  }
  const vec2 walked = terrain::terrain_avatar_ground(*a) - start;
  EXPECT_GT(walked.x, 1.5f) << "3 s steered forward along the camera's +X";
  EXPECT_LT(std::abs(walked.y), 0.3f);
  // A tree request from a terrain player is ignored (no tree), the session and the tick go on.
  c.receive_all();
  c.send_session(protocol::write_tree_request(c.writer_, c.session));
  server.run_tick(now += 33ms);
  EXPECT_FALSE(c.receive(wire::Message::TreeSummary).has_value());
  c.send_input(vec2(0.0f), seq++, kPi / 2);
  for (int i = 0; i < 30; ++i) server.run_tick(now += 33ms);
  EXPECT_EQ(server.num_players(), 1);
  EXPECT_FALSE(a->stepping) << "stopped on a zero direction";
}

TEST(TerrainBots, TheGraphCanStillBeForcedOnTheTerrainScene) {
  TerrainMatch m(1, server::Locomotion::kGraph);
  EXPECT_FALSE(m.server.terrain_mode());
  bots::BotFleet fleet(m.server.library(), m.config);
  m.play(fleet, 30 * 3);
  ASSERT_EQ(m.server.avatar_ids().size(), 1u + static_cast<size_t>(m.server.num_fighters()));
  EXPECT_NE(m.server.avatar(m.server.avatar_ids().back()), nullptr);
  fleet.disconnect_all();
}

}  // namespace
}  // namespace foresight

// Graceful shutdown and restart: the server tells every client it is going (they know at once,
// not after their timeout), and bots reconnect with back-off to the server that comes back on
// the same port. One fake clock drives both sides.
#include "bot_match.hpp"

#include <gtest/gtest.h>

#include <memory>

namespace foresight {
namespace {

using namespace std::chrono_literals;

TEST(Shutdown, ClientsAreToldAndBotsReconnectToTheRestartedServer) {
  std::string error;
  server::ServerConfig config = test::test_server_config("arena");
  auto first = std::make_unique<server::Server>();
  ASSERT_TRUE(first->start(config, error)) << error;
  bots::BotFleetConfig fleet_config;
  ASSERT_TRUE(protocol::parse_endpoint("127.0.0.1:" + std::to_string(first->port()), fleet_config.server, error));
  fleet_config.count = 3;
  fleet_config.script = bots::BotScript::kWander;
  // The bots' own library (the first server's goes with it).
  MotionLibrary library;
  ASSERT_TRUE(motion_library_load(config.motions, library, error)) << error;
  bots::BotFleet fleet(library, fleet_config);
  auto now = server::Clock::now();
  auto play = [&](server::Server* s, int frames) {
    for (int i = 0; i < frames; ++i) {
      now += 33ms;
      if (s) s->run_tick(now);
      fleet.frame(now);
    }
  };
  play(first.get(), 60);
  ASSERT_EQ(fleet.connected_now(), 3);

  first->close_sessions();
  EXPECT_EQ(first->num_players(), 0);
  EXPECT_EQ(first->counters().sessions_closed, 3u);
  EXPECT_EQ(first->counters().refused, 0u) << "a farewell is not a refusal";
  play(first.get(), 2);  // a frame or two, far under the 5 s session timeout
  EXPECT_EQ(fleet.connected_now(), 0);
  EXPECT_EQ(fleet.report(now).server_gone, 3);

  // The server is gone for a second, then back on the same port. Back-off: the first retry comes
  // 0.5 s (+-25 %) after the loss, not at once (a restarted server is not stormed).
  const uint16_t port = first->port();
  first.reset();
  play(nullptr, 8);  // 0.33 s after the loss
  EXPECT_EQ(fleet.report(now).reconnects, 0);
  play(nullptr, 20);  // 1 s
  EXPECT_EQ(fleet.report(now).reconnects, 3) << "each bot tried once, and is still trying";
  config.port = port;
  server::Server second;
  ASSERT_TRUE(second.start(config, error)) << error;
  int frames = 0;
  while (fleet.connected_now() < 3 && frames < 30 * 20) {
    play(&second, 1);
    ++frames;
  }
  EXPECT_EQ(fleet.connected_now(), 3) << "not all back after " << frames << " frames";
  EXPECT_EQ(second.num_players(), 3);
  const bots::BotReport r = fleet.report(now);
  EXPECT_GE(r.reconnects, 3);
  fleet.disconnect_all();
}

TEST(Shutdown, ARawClientSeesTheFarewell) {
  std::string error;
  server::Server s;
  ASSERT_TRUE(s.start(test::test_server_config("arena"), error)) << error;
  auto now = server::Clock::now();
  test::RawClient c(s.port());
  ASSERT_TRUE(c.connect(s, now, s.library().content_hash));
  c.receive_all();
  s.close_sessions();
  int farewells = 0;
  for (auto& d : c.receive_all()) {
    protocol::DropReason reason;
    const wire::Packet* p = protocol::packet_read(d, reason);
    if (p && p->message_as_Refuse() && p->message_as_Refuse()->reason() == wire::RefuseReason::ShuttingDown) ++farewells;
  }
  EXPECT_EQ(farewells, 2);
}

}  // namespace
}  // namespace foresight

namespace foresight {
namespace {

TEST(Churn, BotsLeaveAndJoinAgainAsNewSessions) {
  test::BotMatch m(test::test_server_config("arena"), 3, bots::BotScript::kWander);
  m.config.churn_every_s = 1.0;
  bots::BotFleet fleet(m.server.library(), m.config);
  m.play(fleet, 30 * 8);
  const bots::BotReport r = fleet.report(m.now);
  EXPECT_GE(r.churns, 6);
  EXPECT_GE(m.server.counters().sessions_closed, 6u) << "each leave is a clean Disconnect";
  EXPECT_GE(m.server.counters().sessions_opened, 3u + 6u);
  EXPECT_EQ(m.server.counters().sessions_timed_out, 0u);
  EXPECT_GE(fleet.connected_now(), 2) << "at most the one that just left is away";
  EXPECT_EQ(m.server.num_players(), fleet.connected_now());
  // A bot's kbps are its latest session's bytes over that session's time (its connection's
  // counters span all its sessions): churned bots do not look several times busier.
  const double per_client_kbps = static_cast<double>(m.server.counters().bytes_out) * 8.0 / 1000.0 / 8.0 / 3.0;
  EXPECT_GT(r.down_kbps_p50, 0.5 * per_client_kbps);
  EXPECT_LT(r.down_kbps_p50, 1.5 * per_client_kbps) << "what the server sent, per client and second";
  fleet.disconnect_all();
}

}  // namespace
}  // namespace foresight

namespace foresight {
namespace {

TEST(JoinQueue, ACrowdLargerThanTheHandshakeTimeoutAllowsAllGetsIn) {
  // One join a tick: 180 bots need 6 s, more than the 5 s handshake timeout. The server tells the
  // waiting ones they are queued, which restarts their timeout: nobody gives up.
  server::ServerConfig c = test::test_server_config("field");
  c.max_joins_per_tick = 1;
  c.expansions_per_avatar = 20;
  test::BotMatch m(c, 180, bots::BotScript::kWander);
  m.config.connects_per_frame = 180;
  bots::BotFleet fleet(m.server.library(), m.config);
  m.play(fleet, 30 * 8);
  const bots::BotReport r = fleet.report(m.now);
  EXPECT_EQ(r.timed_out, 0);
  EXPECT_EQ(r.connected_at_end, 180);
  EXPECT_EQ(m.server.num_players(), 180);
  EXPECT_EQ(m.server.counters().refused, 0u) << "\"queued\" is not a refusal";
  EXPECT_GT(m.server.counters().joins_deferred, 100u);
  fleet.disconnect_all();
}

}  // namespace
}  // namespace foresight

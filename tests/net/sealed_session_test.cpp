// Sealed sessions against a real server (issue 8): after the handshake every message is sealed
// with the session's key, so an input that is unsealed, forged (made-up payload, another key),
// replayed, or sent from another address is dropped and counted, and the player's state is what
// its genuine inputs made it. And the keys are the session's own: two players' differ.
#include "raw_client.hpp"

#include <gtest/gtest.h>

namespace foresight {
namespace {

using namespace std::chrono_literals;

size_t dropped(const server::Server& s, protocol::DropReason r) {
  return s.counters().drops.by_reason[static_cast<size_t>(r)];
}

TEST(SealedSession, ForgedReplayedAndUnsealedInputsAreDropped) {
  server::Server server;
  std::string error;
  ASSERT_TRUE(server.start(test::test_server_config("arena"), error)) << error;
  auto now = server::Clock::now();
  test::RawClient player(server.port()), attacker(server.port());
  ASSERT_TRUE(player.connect(server, now, server.library().content_hash));
  const float facing = server.avatar(player.avatar)->root().heading_rad;

  // The player stands still (stop, sequence 1); what reaches the server decides.
  player.send_input(vec2(0.0f), 1, facing);
  server.run_tick(now += 33ms);
  ASSERT_EQ(server.avatar(player.avatar)->input().camera_dir, vec2(0.0f));

  // A genuine "walk" input, sealed by the player, kept by an eavesdropper.
  ControlInput walk;
  walk.camera_dir = {0.0f, 1.0f};
  walk.camera_yaw_rad = facing;
  const wire::InputCommand cmd = protocol::input_command_from(walk, 2);
  protocol::PacketWriter w;
  const std::vector<uint8_t> recorded = player.seal(protocol::write_input(w, player.session, 0, 2, {&cmd, 1}));
  // 1. Unsealed, from the player's own address (spoofed or not): anyone could have sent it.
  player.send_raw([&] {
    const auto b = protocol::write_input(w, player.session, 0, 3, {&cmd, 1});
    return std::vector<uint8_t>(b.begin(), b.end());
  }());
  // 2. Forged: a Sealed message naming the session with a made-up payload.
  {
    auto& fbb = w.begin();
    const std::vector<uint8_t> junk(64, 0x42);
    const auto b = w.finish(wire::CreateSealed(fbb, player.session, 99, fbb.CreateVector(junk)));
    player.send_raw(std::vector<uint8_t>(b.begin(), b.end()));
  }
  // 3. The recorded genuine datagram from another address.
  attacker.send_raw(recorded);
  server.run_tick(now += 33ms);
  EXPECT_EQ(server.avatar(player.avatar)->input().camera_dir, vec2(0.0f)) << "nothing of that reached the avatar";
  EXPECT_EQ(dropped(server, protocol::DropReason::kUnauthenticated), 2u);
  EXPECT_EQ(dropped(server, protocol::DropReason::kUnexpected), 1u) << "not from the player's address";

  // The genuine datagram from the player's address works once; replayed, it is dropped.
  player.send_raw(recorded);
  server.run_tick(now += 33ms);
  EXPECT_EQ(server.avatar(player.avatar)->input().camera_dir, walk.camera_dir);
  player.send_input(vec2(0.0f), 4, facing);  // stop again
  server.run_tick(now += 33ms);
  player.send_raw(recorded);  // replayed after it: would start walking again
  server.run_tick(now += 33ms);
  EXPECT_EQ(dropped(server, protocol::DropReason::kReplayed), 1u);
  EXPECT_EQ(server.avatar(player.avatar)->input().camera_dir, vec2(0.0f));
  EXPECT_EQ(server.num_players(), 1);
}

// The per-player rate limit counts only what the player really sent: datagrams forged with its
// address (its own socket stands in for a spoofer here) are dropped as forgeries and do not spend
// its allowance, so its genuine input still gets through (issue 19: the limit ran before the
// datagram was opened, and a spoofer could silence a player).
TEST(SealedSession, ForgeriesFromAPlayersAddressDoNotSpendItsAllowance) {
  server::ServerConfig config = test::test_server_config("arena");
  config.max_packets_per_s = 30;
  server::Server server;
  std::string error;
  ASSERT_TRUE(server.start(config, error)) << error;
  auto now = server::Clock::now();
  test::RawClient player(server.port());
  ASSERT_TRUE(player.connect(server, now, server.library().content_hash));
  const float facing = server.avatar(player.avatar)->root().heading_rad;
  server.run_tick(now += 1000ms);  // a full bucket
  protocol::PacketWriter w;
  const std::vector<uint8_t> junk(64, 0x42);
  for (uint64_t i = 0; i < 200; ++i) {
    auto& fbb = w.begin();
    const auto b = w.finish(wire::CreateSealed(fbb, player.session, 1000 + i, fbb.CreateVector(junk)));
    player.send_raw(std::vector<uint8_t>(b.begin(), b.end()));
  }
  player.send_input(vec2(0.0f, 1.0f), 1, facing);
  server.run_tick(now += 1ms);
  EXPECT_EQ(dropped(server, protocol::DropReason::kUnauthenticated), 200u);
  EXPECT_EQ(dropped(server, protocol::DropReason::kRateLimited), 0u);
  EXPECT_EQ(server.avatar(player.avatar)->input().camera_dir, vec2(0.0f, 1.0f)) << "the genuine input got through";
  // Its own flood is still limited: a bucket of 30 and a trickle of refill.
  for (uint32_t seq = 2; seq < 102; ++seq) player.send_input(vec2(0.0f, 1.0f), seq, facing);
  server.run_tick(now += 1ms);
  EXPECT_GE(dropped(server, protocol::DropReason::kRateLimited), 65u);
}

TEST(SealedSession, EachSessionHasItsOwnKeysAndSnapshotsAreSealed) {
  server::Server server;
  std::string error;
  ASSERT_TRUE(server.start(test::test_server_config("arena"), error)) << error;
  auto now = server::Clock::now();
  test::RawClient a(server.port()), b(server.port());
  ASSERT_TRUE(a.connect(server, now, server.library().content_hash));
  ASSERT_TRUE(b.connect(server, now, server.library().content_hash));
  // a's sealed input sent from b's address: b's key does not open it.
  ControlInput in;
  const wire::InputCommand cmd = protocol::input_command_from(in, 1);
  protocol::PacketWriter w;
  b.send_raw(a.seal(protocol::write_input(w, a.session, 0, 1, {&cmd, 1})));
  server.run_tick(now += 33ms);
  EXPECT_EQ(dropped(server, protocol::DropReason::kUnauthenticated), 1u);
  // What the server sends a player is sealed: on the wire there is no readable Snapshot.
  for (int i = 0; i < 3; ++i) server.run_tick(now += 33ms);
  int sealed = 0, plain = 0;
  for (auto& d : a.receive_raw()) {
    protocol::DropReason reason;
    const wire::Packet* p = protocol::packet_read(d, reason);
    sealed += p && p->message_as_Sealed() != nullptr;
    plain += p && p->message_as_Snapshot() != nullptr;
  }
  EXPECT_GT(sealed, 0);
  EXPECT_EQ(plain, 0);
}

}  // namespace
}  // namespace foresight

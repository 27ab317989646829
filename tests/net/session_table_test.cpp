// The server's session table without a game (issue 20 item 1): a real client connection over a
// real UDP socket on loopback joins through it, its sealed messages reach the game's handler, the
// game's refusal reaches the client with its reason, and a disconnect or silence ends the session
// and tells the game. And the tables of avatars: handles that outlive what they named.
#include "avatars.hpp"
#include "server_counters.hpp"
#include "session_table.hpp"
#include "transport/client_connection.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <thread>

namespace foresight {
namespace {

using namespace std::chrono_literals;
using server::Clock;

// A game that gives every joiner avatar 100 + n, or refuses when told to, and remembers what it saw.
struct RecordingGame : server::SessionEvents {
  bool refuse = false;
  int joins = 0, inputs = 0, stats_requests = 0;
  std::vector<uint32_t> left;
  bool on_join(server::Session& s, Clock::time_point, wire::RefuseReason& reason, std::string& why) override {
    if (refuse) {
      reason = wire::RefuseReason::NoSpawnPlace;
      why = "the game has no room";
      return false;
    }
    s.avatar_id = 100 + static_cast<uint32_t>(joins++);
    return true;
  }
  void on_message(server::Session&, const wire::Packet& m) override {
    if (m.message_type() == wire::Message::Input) ++inputs;
    if (m.message_type() == wire::Message::StatsRequest) ++stats_requests;
  }
  void on_leave(const server::Session& s) override { left.push_back(s.avatar_id); }
};

struct Loop {
  server::ServerCounters counters;
  server::SessionTable table{counters};
  RecordingGame game;
  protocol::ClientConnection client;
  Clock::time_point now = Clock::now();

  bool open(double timeout_s = 5.0) {
    server::SessionSettings settings;
    settings.library_hash = 0x1234;
    settings.session_timeout_s = timeout_s;
    std::string error;
    return table.open("127.0.0.1", 0, settings, error);
  }
  // One tick of both sides; the real sockets need a moment to carry the datagrams.
  void tick() {
    client.update(now);
    std::this_thread::sleep_for(2ms);
    table.start_tick();
    table.receive(now, game);
    table.admit_joins(now, game);
    table.expire(now, game);
    now += 33ms;
  }
  bool run_until(const std::function<bool()>& done) {
    for (int i = 0; i < 200 && !done(); ++i) tick();
    return done();
  }
};

TEST(SessionTable, AClientJoinsAndItsSealedMessagesReachTheGame) {
  Loop l;
  ASSERT_TRUE(l.open());
  ASSERT_TRUE(l.client.start(protocol::Endpoint(asio::ip::make_address("127.0.0.1"), l.table.port()), 0x1234, "ana", l.now));
  ASSERT_TRUE(l.run_until([&] { return l.client.connected(); })) << l.client.status_message();
  EXPECT_EQ(l.game.joins, 1);
  ASSERT_EQ(l.table.size(), 1u);
  EXPECT_EQ(l.client.accept().avatar, 100u);
  EXPECT_EQ(l.table.sessions()[0].name, "ana");

  ControlInput walk;
  walk.camera_dir = {0.0f, 1.0f};
  l.client.set_input(walk);
  l.client.request_stats();
  ASSERT_TRUE(l.run_until([&] { return l.game.inputs > 0 && l.game.stats_requests > 0; }));
  EXPECT_EQ(l.counters.drops.total(), 0u);

  l.client.disconnect();
  ASSERT_TRUE(l.run_until([&] { return !l.game.left.empty(); }));
  EXPECT_EQ(l.game.left, std::vector<uint32_t>{100});
  EXPECT_EQ(l.table.size(), 0u);
  EXPECT_EQ(l.counters.sessions_closed, 1u);
}

TEST(SessionTable, TheGamesRefusalReachesTheClientWithItsReason) {
  Loop l;
  ASSERT_TRUE(l.open());
  l.game.refuse = true;
  ASSERT_TRUE(l.client.start(protocol::Endpoint(asio::ip::make_address("127.0.0.1"), l.table.port()), 0x1234, "bo", l.now));
  ASSERT_TRUE(l.run_until([&] { return l.client.refuse().reason != wire::RefuseReason::None; }));
  EXPECT_EQ(l.client.refuse().reason, wire::RefuseReason::NoSpawnPlace);
  EXPECT_EQ(l.client.refuse().message, "the game has no room");
  EXPECT_EQ(l.table.size(), 0u);
  EXPECT_TRUE(l.game.left.empty());  // never joined, so never left
}

TEST(SessionTable, ASilentSessionEndsAndTheGameIsTold) {
  Loop l;
  ASSERT_TRUE(l.open(0.5));
  ASSERT_TRUE(l.client.start(protocol::Endpoint(asio::ip::make_address("127.0.0.1"), l.table.port()), 0x1234, "cy", l.now));
  ASSERT_TRUE(l.run_until([&] { return l.client.connected(); }));
  // The client goes quiet: the table's clock runs on without it.
  for (int i = 0; i < 30 && l.table.size() > 0; ++i) {
    l.now += 33ms;
    l.table.expire(l.now, l.game);
  }
  EXPECT_EQ(l.table.size(), 0u);
  EXPECT_EQ(l.game.left, std::vector<uint32_t>{100});
  EXPECT_EQ(l.counters.sessions_timed_out, 1u);
}

TEST(HandleTable, AHandleToARemovedItemReadsAsGoneEvenWhenItsSlotIsReused) {
  server::HandleTable<int> table;
  const server::Handle a = table.add(1), b = table.add(2), c = table.add(3);
  EXPECT_EQ(table.remove(a), 1);
  // Dense: the last item moved into the gap, and every other handle still finds its own.
  ASSERT_EQ(table.size(), 2u);
  EXPECT_EQ(*table.get(b), 2);
  EXPECT_EQ(*table.get(c), 3);
  EXPECT_EQ(table.get(a), nullptr);
  const server::Handle d = table.add(4);  // takes a's slot, with a new generation
  EXPECT_EQ(d.slot, a.slot);
  EXPECT_EQ(table.get(a), nullptr);
  EXPECT_EQ(*table.get(d), 4);
  EXPECT_EQ(table.remove(a), 0);  // a stale handle removes nothing
  EXPECT_EQ(table.size(), 3u);
  for (size_t i = 0; i < table.size(); ++i) EXPECT_EQ(*table.get(table.handle_at(i)), table.items()[i]);
  EXPECT_EQ(table.get(server::Handle{}), nullptr);
}

TEST(Roster, KeepsIdOrderAsAvatarsComeAndGo) {
  server::Roster roster;
  for (uint32_t id : {3u, 5u, 8u, 9u}) roster.add({id, server::AvatarKind::kGraph, {}});
  roster.remove(5);
  roster.add({12, server::AvatarKind::kTerrain, {}});
  std::vector<uint32_t> ids;
  for (const server::RosterEntry& e : roster.entries()) ids.push_back(e.id);
  EXPECT_EQ(ids, (std::vector<uint32_t>{3, 8, 9, 12}));
  EXPECT_EQ(roster.index_of(9), 2);
  EXPECT_EQ(roster.index_of(5), -1);
  EXPECT_EQ(roster.find(12)->kind, server::AvatarKind::kTerrain);
  roster.remove(4);  // not there: nothing happens
  EXPECT_EQ(roster.entries().size(), 4u);
}

}  // namespace
}  // namespace foresight

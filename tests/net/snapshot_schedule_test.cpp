// The server serves each client on its own ticks (server.cpp, Server::snapshots_by): every tick
// sends about snapshot_hz / tick_hz of the snapshots rather than all of them on two ticks of three,
// while each client still gets snapshot_hz a second, numbered one by one. Real server, real UDP.
#include "raw_client.hpp"

#include <gtest/gtest.h>

#include <map>

namespace foresight {
namespace {

using namespace std::chrono_literals;

TEST(SnapshotSchedule, EveryTickServesSomeClientsAndEachGetsItsRateNumberedOneByOne) {
  server::ServerConfig config = test::test_server_config("arena");
  ASSERT_EQ(config.tick_hz, 30);
  ASSERT_EQ(config.snapshot_hz, 20);
  server::Server server;
  std::string error;
  ASSERT_TRUE(server.start(config, error)) << error;
  auto now = server::Clock::now();
  constexpr int kClients = 6;
  std::vector<std::unique_ptr<test::RawClient>> clients;
  for (int c = 0; c < kClients; ++c) {
    clients.push_back(std::make_unique<test::RawClient>(server.port()));
    ASSERT_TRUE(clients.back()->connect(server, now, server.library().content_hash));
  }
  for (auto& c : clients) c->receive_all();
  constexpr int kTicks = 90;  // 3 s
  std::map<uint32_t, std::vector<uint32_t>> numbers;  // per avatar, its snapshots' numbers
  std::vector<int> served_per_tick;
  uint32_t seq = 1;
  for (int t = 0; t < kTicks; ++t) {
    for (auto& c : clients) c->send_input(vec2(0.0f), seq);
    ++seq;
    server.run_tick(now += 33ms);
    int served = 0;
    for (auto& c : clients) {
      bool got = false;
      for (auto& d : c->receive_all()) {
        protocol::DropReason reason;
        const wire::Packet* p = protocol::packet_read(d, reason);
        const wire::Snapshot* s = p ? p->message_as_Snapshot() : nullptr;
        if (s == nullptr || s->part() != 0) continue;
        numbers[c->avatar].push_back(s->tick());
        got = true;
      }
      served += got;
    }
    served_per_tick.push_back(served);
  }
  // Each client: 20 a second (60 in 3 s), its numbers one up each time.
  ASSERT_EQ(numbers.size(), static_cast<size_t>(kClients));
  for (const auto& [avatar, got] : numbers) {
    EXPECT_NEAR(static_cast<double>(got.size()), 60.0, 1.0) << "avatar " << avatar;
    for (size_t k = 1; k < got.size(); ++k) ASSERT_EQ(got[k], got[k - 1] + 1) << "avatar " << avatar;
  }
  // Ticks share the work: six clients on consecutive ids (every phase mod 3 twice) make four a
  // tick, never all six on one tick and none on the next.
  for (int t = 0; t < kTicks; ++t) EXPECT_EQ(served_per_tick[static_cast<size_t>(t)], 4) << "tick " << t;
}

}  // namespace
}  // namespace foresight

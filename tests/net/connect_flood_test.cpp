// The bots' connect flood (bots/connect_flood.hpp) really reaches a server at about its rate, and
// the server answers it only within its budget for unverified addresses.
#include "connect_flood.hpp"
#include "raw_client.hpp"

#include <gtest/gtest.h>

#include <thread>

namespace foresight {
namespace {

using namespace std::chrono_literals;

TEST(ConnectFlood, ReachesTheServerAtItsRate) {
  server::ServerConfig config = test::test_server_config("arena");
  config.max_challenges_per_tick = 16;
  server::Server server;
  std::string error;
  ASSERT_TRUE(server.start(config, error)) << error;
  protocol::Endpoint endpoint;
  ASSERT_TRUE(protocol::parse_endpoint("127.0.0.1:" + std::to_string(server.port()), endpoint, error));
  bots::ConnectFlood flood;
  ASSERT_TRUE(flood.start(endpoint, server.library().content_hash, 4000.0, error)) << error;
  int ticks = 0;
  for (auto end = std::chrono::steady_clock::now() + 1s; std::chrono::steady_clock::now() < end; ++ticks) {
    server.run_tick(server::Clock::now());
    std::this_thread::sleep_for(10ms);
  }
  flood.stop();
  server.run_tick(server::Clock::now());
  const auto& c = server.counters();
  EXPECT_GT(flood.sent(), 3000u);
  EXPECT_LT(flood.sent(), 5000u);
  // Every bogus datagram was seen (loopback drops none at this rate), answered within the budget.
  EXPECT_GE(c.packets_in, flood.sent() * 9 / 10);
  EXPECT_LE(c.challenges_sent + c.refused, static_cast<uint64_t>(ticks + 1) * 16u);
  EXPECT_GT(c.challenges_capped, 0u);
  EXPECT_EQ(server.num_players(), 0) << "no bogus session";
}

}  // namespace
}  // namespace foresight

#pragma once
// A real server and a real bot fleet in one process over loopback UDP, driven by one fake clock:
// a server tick, then a bot frame, 33 ms apart. Deterministic in the server's expansion-budget
// mode, and minutes of play take seconds.
#include "bot_fleet.hpp"
#include "raw_client.hpp"

#include <gtest/gtest.h>

namespace foresight::test {

struct BotMatch {
  server::Server server;
  server::Clock::time_point now = server::Clock::now();
  bots::BotFleetConfig config;

  BotMatch(const server::ServerConfig& server_config, int bots, bots::BotScript script, uint64_t seed = 7) {
    std::string error;
    EXPECT_TRUE(server.start(server_config, error)) << error;
    EXPECT_TRUE(protocol::parse_endpoint("127.0.0.1:" + std::to_string(server.port()), config.server, error));
    config.count = bots;
    config.script = script;
    config.seed = seed;
  }
  /// `frames` of both: a server tick, then a bot frame, 33 ms apart.
  void play(bots::BotFleet& fleet, int frames) {
    for (int i = 0; i < frames; ++i) {
      now += std::chrono::milliseconds(33);
      server.run_tick(now);
      fleet.frame(now);
    }
  }
};

}  // namespace foresight::test

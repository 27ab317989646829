// Agones integration (server/agones_sdk.hpp, docs/SCALING.md): a real server and, on loopback, an
// HTTP server standing in for the Agones SDK sidecar (the real one runs only in a cluster, beside
// the game server in its pod). Ready once the ticks run (retried while the sidecar refuses),
// Health while they keep coming and not while they stall, Shutdown at the graceful shutdown.
#include "raw_client.hpp"

#include <httplib.h>

#include <gtest/gtest.h>

#include <atomic>
#include <thread>

namespace foresight {
namespace {

using namespace std::chrono_literals;

struct Sidecar {
  httplib::Server http;
  std::atomic<int> ready_calls{0}, health{0}, shutdown{0};
  const int refuse_first_readies;
  int port = 0;
  std::thread thread;

  explicit Sidecar(int refuse_first_readies_) : refuse_first_readies(refuse_first_readies_) {
    http.Post("/ready", [this](const httplib::Request&, httplib::Response& res) {
      res.status = ready_calls.fetch_add(1) < refuse_first_readies ? 503 : 200;
      res.set_content("{}", "application/json");
    });
    http.Post("/health", [this](const httplib::Request&, httplib::Response& res) {
      ++health;
      res.set_content("{}", "application/json");
    });
    http.Post("/shutdown", [this](const httplib::Request&, httplib::Response& res) {
      ++shutdown;
      res.set_content("{}", "application/json");
    });
    port = http.bind_to_any_port("127.0.0.1");
    thread = std::thread([this] { http.listen_after_bind(); });
  }
  ~Sidecar() {
    http.stop();
    thread.join();
  }
};

TEST(Agones, ReadyOnceTickingHealthWhileTickingShutdownAtTheEnd) {
  Sidecar sidecar(2);  // refuses the first two Ready calls (not up yet): the server keeps asking
  ASSERT_GT(sidecar.port, 0);
  server::ServerConfig config = test::test_server_config("arena");
  config.agones_sdk_port = sidecar.port;
  config.agones_health_s = 0.05;
  server::Server server;
  std::string error;
  ASSERT_TRUE(server.start(config, error)) << error;
  std::this_thread::sleep_for(300ms);
  EXPECT_EQ(sidecar.ready_calls.load(), 0) << "not Ready before the first tick";

  const auto tick_for = [&](std::chrono::milliseconds d) {
    for (auto end = std::chrono::steady_clock::now() + d; std::chrono::steady_clock::now() < end;) {
      server.run_tick(server::Clock::now());
      std::this_thread::sleep_for(10ms);
    }
  };
  tick_for(2500ms);
  ASSERT_TRUE(server.agones() != nullptr);
  EXPECT_TRUE(server.agones()->ready());
  EXPECT_EQ(sidecar.ready_calls.load(), 3) << "two refused, the third answered, then no more";
  const int pinged = sidecar.health.load();
  EXPECT_GE(pinged, 5);

  // A stalled tick: once no tick came for 1 s the pings stop, so Agones would mark the instance
  // Unhealthy.
  std::this_thread::sleep_for(1200ms);
  const int stalled = sidecar.health.load();
  std::this_thread::sleep_for(600ms);
  EXPECT_LE(sidecar.health.load() - stalled, 1) << "no pings while the tick is stalled";
  tick_for(500ms);
  EXPECT_GT(sidecar.health.load(), stalled + 2) << "and they resume with the ticks";

  // Graceful shutdown: the clients are told, then the sidecar.
  test::RawClient c(server.port());
  auto now = server::Clock::now();
  ASSERT_TRUE(c.connect(server, now, server.library().content_hash));
  server.close_sessions();
  EXPECT_EQ(sidecar.shutdown.load(), 1);
  server.close_sessions();
  EXPECT_EQ(sidecar.shutdown.load(), 1) << "once";
}

TEST(Agones, WithoutTheOptionThereIsNoSdkClient) {
  server::Server server;
  std::string error;
  ASSERT_TRUE(server.start(test::test_server_config("arena"), error)) << error;
  EXPECT_EQ(server.agones(), nullptr);
}

}  // namespace
}  // namespace foresight

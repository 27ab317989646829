// The tick's threads in the real-time class (server/thread_priority.hpp): where the system allows
// it (root, CAP_SYS_NICE, or an RLIMIT_RTPRIO), the tick thread and every look-ahead worker run in
// the FIFO class and the server ticks; where it does not (a container's default capabilities), the
// refusal says what to grant and the server ticks all the same, at normal priority; /metrics says
// which.
#include "lookahead_workers.hpp"
#include "raw_client.hpp"  // test_server_config
#include "server.hpp"
#include "thread_priority.hpp"

#include <gtest/gtest.h>
#include <httplib.h>

#include <atomic>
#include <chrono>
#include <string>
#include <thread>

namespace foresight {
namespace {

// Whether this process may use the FIFO class, asked of a thread of its own.
bool system_allows_realtime() {
  bool allowed = false;
  std::thread probe([&allowed] {
    std::string error;
    allowed = server::make_realtime(pthread_self(), 1, error);
  });
  probe.join();
  return allowed;
}

TEST(ThreadPriority, TheWorkersEnterTheFifoClassOrSayWhyNot) {
  server::LookaheadWorkers workers(3);
  EXPECT_FALSE(workers.realtime()) << "threads start in the normal class";
  std::string error;
  const bool made = workers.make_realtime(1, error);
  EXPECT_EQ(made, system_allows_realtime());
  EXPECT_EQ(workers.realtime(), made);
  if (!made) {
    EXPECT_NE(error.find("CAP_SYS_NICE"), std::string::npos) << error;
  }
  // They still do the work, in whichever class.
  std::atomic<int> runs{0};
  workers.run(100, [&runs](int, int) { ++runs; });
  EXPECT_EQ(runs.load(), 100);
}

TEST(ThreadPriority, APriorityOutsideTheRangeIsRefusedWithItsReason) {
  std::string error;
  EXPECT_FALSE(server::make_realtime(pthread_self(), 100, error));
  EXPECT_NE(error.find("100"), std::string::npos) << error;
  EXPECT_FALSE(server::is_realtime(pthread_self()));
}

TEST(ThreadPriority, TheServerTicksInTheRealTimeClassWhereAllowedAndAtNormalPriorityWhereNot) {
  server::ServerConfig c = test::test_server_config("maze");
  c.threads = 2;
  c.realtime_priority = 5;
  c.admin_port = 0;  // the admin endpoint reports the class
  c.admin_token = "secret";
  server::Server server;
  std::string error;
  ASSERT_TRUE(server.start(c, error)) << error;
  std::atomic<bool> tick_thread_realtime{false};
  std::thread ticking([&] {
    server.run();
    tick_thread_realtime = server::is_realtime(pthread_self());
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(400));
  httplib::Client admin("127.0.0.1", server.admin_port());
  const auto metrics = admin.Get("/metrics", {{"Authorization", "Bearer secret"}});
  server.stop();
  ticking.join();
  EXPECT_GE(server.tick(), 6u) << "400 ms at 30 Hz";
  EXPECT_EQ(server.realtime(), system_allows_realtime());
  EXPECT_EQ(tick_thread_realtime.load(), server.realtime());
  ASSERT_TRUE(metrics) << "the admin endpoint answers";
  const std::string line = std::string("\nforesight_tick_realtime ") + (server.realtime() ? "1" : "0") + "\n";
  EXPECT_NE(metrics->body.find(line), std::string::npos) << metrics->body.substr(0, 400);
}

}  // namespace
}  // namespace foresight

// The tick thread's scheduler counters (server/thread_sched.hpp), read from the kernel: time on a
// CPU grows while the thread works and not while it sleeps; neither counter goes backwards.
#include "thread_sched.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>

namespace foresight {
namespace {

TEST(ThreadSchedClock, CountsTheThreadsOwnTimeOnACpu) {
  const server::ThreadSchedClock clock;
  ASSERT_TRUE(clock.available()) << "Linux offers /proc/thread-self/schedstat";
  const server::ThreadSchedTimes before = clock.read();
  volatile double sink = 0;
  const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(30);
  while (std::chrono::steady_clock::now() < until) sink = sink + std::sqrt(static_cast<double>(sink) + 2.0);
  const server::ThreadSchedTimes worked = clock.read();
  EXPECT_GT(worked.on_cpu_ns, before.on_cpu_ns + 1'000'000u) << "30 ms of work, at least 1 ms of it on a CPU";
  EXPECT_GE(worked.waiting_ns, before.waiting_ns);
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  const server::ThreadSchedTimes slept = clock.read();
  EXPECT_LT(slept.on_cpu_ns - worked.on_cpu_ns, 20'000'000u) << "50 ms asleep is not time on a CPU";
  // Another thread's counters are its own.
  server::ThreadSchedTimes other;
  std::thread([&] {
    const server::ThreadSchedClock own;
    other = own.read();
  }).join();
  EXPECT_LT(other.on_cpu_ns, slept.on_cpu_ns);
}

}  // namespace
}  // namespace foresight

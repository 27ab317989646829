// The tick's parallel stages (server/lookahead_workers.hpp): every item runs once, one thread's
// calls never overlap (its builder and batch are its own), and a worker that is slow to get on
// with its items leaves the rest to the tick thread instead of holding the tick for them.
#include "lookahead_workers.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

namespace foresight {
namespace {

TEST(LookaheadWorkers, EveryItemRunsOnceAndAThreadsCallsNeverOverlap) {
  for (const int threads : {1, 2, 3}) {
    server::LookaheadWorkers workers(threads);
    for (const int items : {0, 1, 2, 7, 100, 1000}) {
      for (int round = 0; round < 20; ++round) {
        std::vector<std::atomic<int>> runs(static_cast<size_t>(items));
        std::vector<std::atomic<int>> busy(static_cast<size_t>(threads));
        std::atomic<int> overlaps{0}, bad_worker{0};
        workers.run(items, [&](int item, int worker) {
          if (worker < 0 || worker >= threads) {
            ++bad_worker;
            return;
          }
          if (busy[static_cast<size_t>(worker)].fetch_add(1) != 0) ++overlaps;
          ++runs[static_cast<size_t>(item)];
          busy[static_cast<size_t>(worker)].fetch_sub(1);
        });
        int once = 0;
        for (const auto& r : runs) once += r.load() == 1 ? 1 : 0;
        ASSERT_EQ(once, items) << threads << " threads, " << items << " items, round " << round;
        ASSERT_EQ(overlaps.load(), 0);
        ASSERT_EQ(bad_worker.load(), 0);
      }
    }
  }
}

TEST(LookaheadWorkers, TheOtherThreadsTakeWorkWhenThereIsWorkToTake) {
  server::LookaheadWorkers workers(2);
  // Items long enough that the worker, once woken, finds some left.
  for (int round = 0; round < 50 && workers.items_by_others() == 0; ++round)
    workers.run(64, [](int, int) { std::this_thread::sleep_for(std::chrono::microseconds(200)); });
  EXPECT_GT(workers.items_by_others(), 0);
}

// The worker's items are slow (as if the machine ran it a little at a time): the tick thread,
// which would have had half the items with a fixed split, takes all but the few the worker
// claimed.
TEST(LookaheadWorkers, ASlowWorkerLeavesItsShareToTheTickThread) {
  server::LookaheadWorkers workers(2);
  constexpr int kItems = 320;  // claims of 10 items
  std::atomic<int> by_tick_thread{0};
  workers.run(kItems, [&](int, int worker) {
    if (worker == 0) {
      ++by_tick_thread;
    } else {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  });
  EXPECT_GT(by_tick_thread.load(), kItems * 3 / 4) << "a fixed split gives each thread half";
}

}  // namespace
}  // namespace foresight

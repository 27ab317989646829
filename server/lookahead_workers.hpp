#pragma once
// The tick's parallel stages (look-ahead growth, snapshot sending) on several cores. Items are
// independent (a tree reads only the shared, read-only library and scene; a client's snapshot
// only the tick's read-only frame), so the threads claim them a few at a time from a shared
// counter: the tick thread works alongside the others, and a worker the machine does not run
// in time (the other core busy, the hypervisor holding it) leaves its items to the threads that
// do run instead of holding the tick until it wakes.
#include <atomic>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace foresight::server {

class LookaheadWorkers {
 public:
  /// `threads` >= 1 workers in all, the tick thread included.
  explicit LookaheadWorkers(int threads);
  ~LookaheadWorkers();
  LookaheadWorkers(const LookaheadWorkers&) = delete;
  LookaheadWorkers& operator=(const LookaheadWorkers&) = delete;

  int threads() const { return static_cast<int>(pool_.size()) + 1; }
  /// Calls job(item, worker) once for every item in [0, items), each on whichever thread claims
  /// it (`worker`: 0 for the calling thread, 1.. for the others; one thread's calls never
  /// overlap); returns when all are done. `job` must not throw.
  void run(int items, const std::function<void(int item, int worker)>& job);
  /// Puts every worker (not the caller) in the real-time FIFO class (thread_priority.hpp).
  bool make_realtime(int priority, std::string& error);
  /// Every worker is in the FIFO class (true with no workers).
  bool realtime();
  /// Items claimed by threads other than the caller since construction (tests: work is shared).
  long long items_by_others() const { return items_by_others_.load(std::memory_order_relaxed); }

 private:
  void worker_main(int worker);
  /// Claims and runs items until none is left; returns how many it ran.
  int drain(const std::function<void(int, int)>& job, int items, int worker);

  std::vector<std::thread> pool_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  const std::function<void(int, int)>* job_ = nullptr;
  int items_ = 0;
  int grain_ = 1;
  std::atomic<int> next_{0};  ///< The next unclaimed item.
  uint64_t generation_ = 0;
  bool open_ = false;  ///< A run is taking workers (they join only while it is).
  int inside_ = 0;     ///< Workers in the current run: it returns once they have left.
  bool stop_ = false;
  std::atomic<long long> items_by_others_{0};
};

}  // namespace foresight::server

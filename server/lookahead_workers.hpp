#pragma once
// The look-ahead phase of the tick on several cores. Trees are independent (each reads only the
// shared, read-only library and scene), so avatars are split into contiguous chunks, one per
// thread; the tick thread works the first chunk itself and waits for the others.
#include <condition_variable>
#include <functional>
#include <mutex>
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
  /// Calls job(item, worker) for every item in [0, items), chunked over the workers; returns when
  /// all are done. `job` must not throw.
  void run(int items, const std::function<void(int item, int worker)>& job);

 private:
  void worker_main(int worker);

  std::vector<std::thread> pool_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  const std::function<void(int, int)>* job_ = nullptr;
  int items_ = 0;
  uint64_t generation_ = 0;
  int pending_ = 0;
  bool stop_ = false;
};

}  // namespace foresight::server

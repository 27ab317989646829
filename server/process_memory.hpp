#pragma once
// The server process's memory as the system sees it: its resident set, and the heap settings and
// upkeep that make that resident set follow the work (issue 20 item 5; docs/PERFORMANCE.md
// "Server memory per player").
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>

namespace foresight::server {

/// The process's resident set in bytes (0 where /proc is not there).
uint64_t resident_memory_bytes();

/// Once, before anything is allocated: a fixed mmap threshold, so that every large block (a
/// session's buffers, a large leaf queue) is its own mapping, returned to the system when freed.
void configure_heap();

/// Returns the heap's free pages to the system (glibc's malloc_trim): motion-tree chunks and
/// queues freed as trees shrink leave holes between live blocks that free() alone never gives
/// back, so without this the resident set stays at its peak (the first players get the whole
/// budget and grow the largest trees). Returns the milliseconds it took (about 1 ms for 200
/// players), so the caller can report it.
double release_free_heap();

/// release_free_heap() every `every`, on a thread of its own at the lowest priority, never in the
/// tick: at 1000 players it takes 14-17 ms, and run in the tick it made that tick overrun (two of
/// five overruns in two 1000-bot runs, docs/PERFORMANCE.md). Stops (and joins) when destroyed.
class HeapTrimmer {
 public:
  explicit HeapTrimmer(std::chrono::milliseconds every);
  ~HeapTrimmer();
  HeapTrimmer(const HeapTrimmer&) = delete;
  HeapTrimmer& operator=(const HeapTrimmer&) = delete;

  /// Milliseconds the last trim took (0 before the first).
  double last_ms() const { return last_ms_.load(std::memory_order_relaxed); }
  /// Trims done so far.
  uint64_t trims() const { return trims_.load(std::memory_order_relaxed); }

 private:
  void run(std::chrono::milliseconds every);

  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::atomic<double> last_ms_{0.0};
  std::atomic<uint64_t> trims_{0};
  std::thread thread_;  ///< Last: started once the rest is there.
};

}  // namespace foresight::server

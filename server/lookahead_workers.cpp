#include "lookahead_workers.hpp"

#include "thread_priority.hpp"

#include <algorithm>

namespace foresight::server {

LookaheadWorkers::LookaheadWorkers(int threads) {
  for (int w = 1; w < std::max(threads, 1); ++w) pool_.emplace_back([this, w] { worker_main(w); });
}

LookaheadWorkers::~LookaheadWorkers() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : pool_) t.join();
}

bool LookaheadWorkers::make_realtime(int priority, std::string& error) {
  for (std::thread& t : pool_)
    if (!server::make_realtime(t.native_handle(), priority, error)) return false;
  return true;
}

bool LookaheadWorkers::realtime() {
  for (std::thread& t : pool_)
    if (!is_realtime(t.native_handle())) return false;
  return true;
}

int LookaheadWorkers::drain(const std::function<void(int, int)>& job, int items, int worker) {
  int ran = 0;
  for (;;) {
    const int first = next_.fetch_add(grain_, std::memory_order_relaxed);
    if (first >= items) return ran;
    const int end = std::min(first + grain_, items);
    for (int i = first; i < end; ++i) job(i, worker);
    ran += end - first;
  }
}

void LookaheadWorkers::run(int items, const std::function<void(int, int)>& job) {
  if (pool_.empty() || items <= 1) {
    for (int i = 0; i < items; ++i) job(i, 0);
    return;
  }
  {
    std::lock_guard lock(mutex_);
    job_ = &job;
    items_ = items;
    // About 16 claims a thread: fine enough that a late thread's share is small, coarse enough
    // that the shared counter is touched a few dozen times a run.
    grain_ = std::max(1, items / (threads() * 16));
    next_.store(0, std::memory_order_relaxed);
    ++generation_;
    open_ = true;
  }
  wake_.notify_all();
  drain(job, items, 0);
  // Every item is claimed: close the run to workers not yet in it, and wait for those in it to
  // finish the items they claimed.
  std::unique_lock lock(mutex_);
  open_ = false;
  done_.wait(lock, [this] { return inside_ == 0; });
  job_ = nullptr;
}

void LookaheadWorkers::worker_main(int worker) {
  uint64_t seen = 0;
  for (;;) {
    const std::function<void(int, int)>* job = nullptr;
    int items = 0;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || (open_ && generation_ != seen); });
      if (stop_) return;
      seen = generation_;
      job = job_;
      items = items_;
      ++inside_;
    }
    const int ran = drain(*job, items, worker);
    items_by_others_.fetch_add(ran, std::memory_order_relaxed);
    {
      std::lock_guard lock(mutex_);
      --inside_;
    }
    done_.notify_one();
  }
}

}  // namespace foresight::server

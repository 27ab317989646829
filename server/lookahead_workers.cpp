#include "lookahead_workers.hpp"

#include <algorithm>

namespace foresight::server {

namespace {
void run_chunk(const std::function<void(int, int)>& job, int items, int workers, int worker) {
  const int begin = items * worker / workers, end = items * (worker + 1) / workers;
  for (int i = begin; i < end; ++i) job(i, worker);
}
}  // namespace

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

void LookaheadWorkers::run(int items, const std::function<void(int, int)>& job) {
  if (pool_.empty()) {
    run_chunk(job, items, 1, 0);
    return;
  }
  {
    std::lock_guard lock(mutex_);
    job_ = &job;
    items_ = items;
    pending_ = static_cast<int>(pool_.size());
    ++generation_;
  }
  wake_.notify_all();
  run_chunk(job, items, threads(), 0);
  std::unique_lock lock(mutex_);
  done_.wait(lock, [this] { return pending_ == 0; });
  job_ = nullptr;
}

void LookaheadWorkers::worker_main(int worker) {
  uint64_t seen = 0;
  for (;;) {
    const std::function<void(int, int)>* job = nullptr;
    int items = 0;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
      job = job_;
      items = items_;
    }
    run_chunk(*job, items, threads(), worker);
    {
      std::lock_guard lock(mutex_);
      --pending_;
    }
    done_.notify_one();
  }
}

}  // namespace foresight::server

#include "process_memory.hpp"

#include <chrono>
#include <cstdio>

#include <malloc.h>
#include <sys/resource.h>
#include <unistd.h>

namespace foresight::server {

uint64_t resident_memory_bytes() {
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  if (f == nullptr) return 0;
  unsigned long long pages_total = 0, pages_resident = 0;
  const int read = std::fscanf(f, "%llu %llu", &pages_total, &pages_resident);
  std::fclose(f);
  return read == 2 ? pages_resident * static_cast<uint64_t>(sysconf(_SC_PAGESIZE)) : 0;
}

void configure_heap() {
  // glibc serves blocks over the mmap threshold with their own mappings, but raises that threshold
  // (up to 32 MB) each time such a block is freed, after which large blocks come from the heap
  // and their freed memory stays resident. A fixed threshold keeps them in their own mappings.
  mallopt(M_MMAP_THRESHOLD, 64 * 1024);
}

double release_free_heap() {
  const auto start = std::chrono::steady_clock::now();
  malloc_trim(0);
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

HeapTrimmer::HeapTrimmer(std::chrono::milliseconds every) : thread_([this, every] { run(every); }) {}

HeapTrimmer::~HeapTrimmer() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void HeapTrimmer::run(std::chrono::milliseconds every) {
  // The lowest priority this thread may take (Linux: a thread's own nice value): the tick and the
  // look-ahead workers always come first. Failing that it trims at the normal priority.
  setpriority(PRIO_PROCESS, static_cast<id_t>(gettid()), 19);
  std::unique_lock<std::mutex> lock(mutex_);
  while (!wake_.wait_for(lock, every, [this] { return stop_; })) {
    lock.unlock();
    last_ms_.store(release_free_heap(), std::memory_order_relaxed);
    trims_.fetch_add(1, std::memory_order_relaxed);
    lock.lock();
  }
}

}  // namespace foresight::server

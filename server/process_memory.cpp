#include "process_memory.hpp"

#include <chrono>
#include <cstdio>

#include <malloc.h>
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

}  // namespace foresight::server

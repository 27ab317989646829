#include "thread_sched.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cstdlib>

namespace foresight::server {

ThreadSchedClock::ThreadSchedClock() : fd_(::open("/proc/thread-self/schedstat", O_RDONLY | O_CLOEXEC)) {}

ThreadSchedClock::~ThreadSchedClock() {
  if (fd_ >= 0) ::close(fd_);
}

ThreadSchedTimes ThreadSchedClock::read() const {
  ThreadSchedTimes t;
  if (fd_ < 0) return t;
  char buf[96];
  const ssize_t n = ::pread(fd_, buf, sizeof buf - 1, 0);
  if (n <= 0) return t;
  buf[n] = '\0';
  // "<ns on a CPU> <ns waiting on a run queue> <time slices>"
  char* end = nullptr;
  t.on_cpu_ns = std::strtoull(buf, &end, 10);
  t.waiting_ns = std::strtoull(end, nullptr, 10);
  return t;
}

}  // namespace foresight::server

#pragma once
// The calling thread's time on a CPU and time runnable but waiting for one, as the kernel's
// scheduler counts them (Linux: /proc/thread-self/schedstat). An overrun line says with them
// whether a slow tick was work or a thread the machine did not run: time waiting for a CPU is
// other tasks on the cores (here the bots); time in neither, in a tick that did not sleep or
// wait for its workers, is what the hypervisor took (steal) or the kernel spent elsewhere.
#include <cstdint>

namespace foresight::server {

struct ThreadSchedTimes {
  uint64_t on_cpu_ns = 0;
  uint64_t waiting_ns = 0;
};

class ThreadSchedClock {
 public:
  /// Opens the calling thread's counters; read them on that thread only.
  ThreadSchedClock();
  ~ThreadSchedClock();
  ThreadSchedClock(const ThreadSchedClock&) = delete;
  ThreadSchedClock& operator=(const ThreadSchedClock&) = delete;
  /// False where the kernel does not offer them (then every read is zeros).
  bool available() const { return fd_ >= 0; }
  ThreadSchedTimes read() const;  ///< One pread: a few microseconds.

 private:
  int fd_ = -1;
};

}  // namespace foresight::server

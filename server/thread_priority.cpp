#include "thread_priority.hpp"

#include <pthread.h>
#include <sched.h>

#include <cstring>

namespace foresight::server {

bool make_realtime(std::thread::native_handle_type thread, int priority, std::string& error) {
  sched_param param{};
  param.sched_priority = priority;
  const int failed = pthread_setschedparam(thread, SCHED_FIFO, &param);
  if (failed == 0) return true;
  error = std::string("real-time priority ") + std::to_string(priority) + " refused: " + std::strerror(failed) +
          (failed == EPERM ? " (grant CAP_SYS_NICE, or `ulimit -r " + std::to_string(priority) +
                                 "` / LimitRTPRIO=, or start with --realtime-priority 0)"
                           : "");
  return false;
}

bool is_realtime(std::thread::native_handle_type thread) {
  int policy = 0;
  sched_param param{};
  return pthread_getschedparam(thread, &policy, &param) == 0 && policy == SCHED_FIFO;
}

}  // namespace foresight::server

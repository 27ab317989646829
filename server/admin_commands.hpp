#pragma once
// The supervisor's commands (paper 3.5: a supervisor orders the fighter to punch or kick), typed
// on the server's console (`foresight-server --console`) until the admin endpoint of issue 8:
//   fighters                      list the fighters: id, morphology, phase, target, strikes
//   order <id|all> punch|kick|any order a strike at the target's head as it is now
//   auto <on|off>                 the fighters' own policy (strike in reach after a cool-down)
//   help
// Lines are queued from the console thread (post) and run on the tick thread (Server::run_tick),
// so a command never races the simulation.
#include <mutex>
#include <string>
#include <vector>

namespace foresight::server {

class AdminQueue {
 public:
  /// Any thread.
  void post(std::string line) {
    std::lock_guard<std::mutex> lock(mutex_);
    lines_.push_back(std::move(line));
  }
  /// The tick thread: moves the waiting lines into `out` (cleared first).
  void take(std::vector<std::string>& out) {
    out.clear();
    std::lock_guard<std::mutex> lock(mutex_);
    out.swap(lines_);
  }

 private:
  std::mutex mutex_;
  std::vector<std::string> lines_;
};

}  // namespace foresight::server

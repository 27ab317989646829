#pragma once
// The supervisor's and the admin's commands (Server::admin_command), typed on the server's console
// (`foresight-server --console`) or posted to the admin endpoint (POST /command, admin_http.hpp):
//   fighters                      list the fighters: id, morphology, phase, target, strikes
//   order <id|all> punch|kick|any order a strike at the target's head as it is now (paper 3.5)
//   auto <on|off>                 the fighters' own policy (strike in reach after a cool-down)
//   set budget-ms <ms>            look-ahead budget per tick, at most (0-1000)
//   set avatar-budget-ms <ms>     look-ahead time one avatar may take per tick (0: no cap)
//   set margin-ms <ms>            tick time kept free of look-ahead (0-1000)
//   set strategy <name>           exploration strategy (trees keep their root and regrow)
//   set resort-ticks <n>          re-prioritise trees at least every n ticks (1-1000)
//   help
// Lines are queued from any thread (post) and run on the tick thread at the start of the next
// tick (Server::run_tick), so a command never races the simulation; the reply goes to the
// poster's callback, or to stdout when it gave none. A reply carries an HTTP-style status: 200
// done, 400 a malformed command (a bad value, a missing or an extra word: nothing is applied),
// 404 an unknown command, setting or fighter.
#include <functional>
#include <mutex>
#include <string>
#include <vector>

namespace foresight::server {

struct AdminReply {
  int status = 200;  ///< 200 done, 400 malformed (not applied), 404 unknown.
  std::string text;
};

struct AdminRequest {
  std::string line;
  std::function<void(const AdminReply& reply)> reply;  ///< Called on the tick thread; may be empty.
};

class AdminQueue {
 public:
  /// Any thread.
  void post(std::string line, std::function<void(const AdminReply&)> reply = {}) {
    std::lock_guard<std::mutex> lock(mutex_);
    requests_.push_back({std::move(line), std::move(reply)});
  }
  /// The tick thread: moves the waiting requests into `out` (cleared first).
  void take(std::vector<AdminRequest>& out) {
    out.clear();
    std::lock_guard<std::mutex> lock(mutex_);
    out.swap(requests_);
  }

 private:
  std::mutex mutex_;
  std::vector<AdminRequest> requests_;
};

}  // namespace foresight::server

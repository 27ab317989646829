#pragma once
// The look-ahead: before the tick decides, each avatar's tree takes its player's new command
// (take_inputs); after the tick has decided, played and sent, every motion-graph avatar's
// feasible motion tree grows for the decisions of the ticks to come (grow) within what the tick
// leaves (the period minus the time spent so far, how far the stage ran past its budget lately,
// and the safety margin; capped by lookahead_budget_ms), shared by need (a thin tree or a
// decision coming soon asks for more), on the worker threads. The stage is last so that it, and
// nothing else, takes up the tick's slack: a slow receive, advance or send (a busy machine)
// shortens the growth instead of running the tick over. With expansions_per_avatar set, each
// tree grows by that many expansions instead (deterministic tests).
#include "avatars.hpp"
#include "clock.hpp"
#include "lookahead_workers.hpp"
#include "server_config.hpp"
#include "tick_stats.hpp"

#include <chrono>
#include <span>
#include <vector>

namespace foresight::server {

class LookaheadScheduler {
 public:
  LookaheadScheduler(const ServerConfig& config, const MotionLibrary& library, LookaheadWorkers& workers);
  /// Gives each avatar's tree its player's command when it changed or a decision is coming (to
  /// re-rank from where the avatar stands, when the tree is next used), so that the tick decides
  /// under the newest command. On the tick thread.
  void take_inputs(std::span<GraphAvatar> avatars);
  /// Grows the trees of `avatars` until the tick's deadline; fills the record's budget,
  /// look-ahead time, expansions and tree sizes. `tick_start` is when the tick began, on the real clock.
  void grow(std::span<GraphAvatar> avatars, uint32_t tick, Clock::time_point tick_start, TickRecord& record);

 private:
  const ServerConfig& config_;
  const MotionLibrary& library_;
  LookaheadWorkers& workers_;
  double overrun_ms_ = 0;              ///< How far the stage ran past its budget lately (EMA).
  std::vector<double> weight_;         ///< Per avatar, reused.
  std::vector<int64_t> expansions_;    ///< Per avatar, this tick.
};

}  // namespace foresight::server

#pragma once
// The look-ahead stage: every motion-graph avatar's feasible motion tree grows within what the
// tick leaves (the period minus the time spent so far, what advancing and sending took lately,
// and the safety margin; capped by lookahead_budget_ms), shared by need (a thin tree or a decision
// coming soon asks for more), on the worker threads. With expansions_per_avatar set, each tree
// grows by that many expansions instead (deterministic tests).
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
  /// Grows the trees of `avatars`; fills the record's budget, look-ahead time, expansions and tree
  /// sizes. `tick_start` is when the tick began, on the real clock.
  void grow(std::span<GraphAvatar> avatars, uint32_t tick, Clock::time_point tick_start, TickRecord& record);
  /// What the stages after the look-ahead took this tick: the next budget leaves room for them.
  void note_tail_ms(double ms) { tail_ms_estimate_ = 0.9 * tail_ms_estimate_ + 0.1 * ms; }

 private:
  const ServerConfig& config_;
  const MotionLibrary& library_;
  LookaheadWorkers& workers_;
  double tail_ms_estimate_ = 0;        ///< Recent advance + send time (EMA), kept out of the budget.
  std::vector<double> weight_;         ///< Per avatar, reused.
  std::vector<int64_t> expansions_;    ///< Per avatar, this tick.
};

}  // namespace foresight::server

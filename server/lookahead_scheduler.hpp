#pragma once
// The look-ahead stage: every motion-graph avatar's feasible motion tree grows within what the
// tick leaves (the period minus the time spent so far, what advancing and sending take on the
// slow ticks of late, how far the stage itself ran past its budget lately, and the safety margin;
// capped by lookahead_budget_ms), shared by need (a thin tree or a decision coming soon asks for
// more), on the worker threads. With expansions_per_avatar set, each tree grows by that many
// expansions instead (deterministic tests).
#include "avatars.hpp"
#include "clock.hpp"
#include "lookahead_workers.hpp"
#include "server_config.hpp"
#include "tick_stats.hpp"

#include <array>
#include <chrono>
#include <span>
#include <vector>

namespace foresight::server {

/// What the stages after the look-ahead will take, from what they took on the last 64 ticks: the
/// larger of their mean (smoothed) and their 90th percentile. On a machine that is busy (the
/// 1000-bot field on 2 shared cores) those stages vary by several milliseconds from tick to tick,
/// and a budget sized on their mean ran the slow ticks over the period.
class TailEstimate {
 public:
  void note(double ms);
  double ms() const;

 private:
  std::array<double, 64> recent_{};
  size_t count_ = 0;
  double mean_ = 0;
};

class LookaheadScheduler {
 public:
  LookaheadScheduler(const ServerConfig& config, const MotionLibrary& library, LookaheadWorkers& workers);
  /// Grows the trees of `avatars`; fills the record's budget, look-ahead time, expansions and tree
  /// sizes. `tick_start` is when the tick began, on the real clock.
  void grow(std::span<GraphAvatar> avatars, uint32_t tick, Clock::time_point tick_start, TickRecord& record);
  /// What the stages after the look-ahead took this tick: the next budget leaves room for them.
  void note_tail_ms(double ms) { tail_.note(ms); }

 private:
  const ServerConfig& config_;
  const MotionLibrary& library_;
  LookaheadWorkers& workers_;
  TailEstimate tail_;                  ///< Advance + send, kept out of the budget.
  double overrun_ms_ = 0;              ///< How far the stage ran past its budget lately (EMA).
  std::vector<double> weight_;         ///< Per avatar, reused.
  std::vector<int64_t> expansions_;    ///< Per avatar, this tick.
};

}  // namespace foresight::server

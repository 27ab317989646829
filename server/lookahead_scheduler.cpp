#include "lookahead_scheduler.hpp"

#include <algorithm>
#include <climits>

namespace foresight::server {

LookaheadScheduler::LookaheadScheduler(const ServerConfig& config, const MotionLibrary& library,
                                       LookaheadWorkers& workers)
    : config_(config), library_(library), workers_(workers) {}

namespace {

int frames_left(const MotionLibrary& library, const LookaheadAvatar& a) {
  return library.graph.segments[static_cast<size_t>(a.playback().segment)].num_frames() - a.playback().frame;
}

}  // namespace

void LookaheadScheduler::take_inputs(std::span<GraphAvatar> avatars) {
  // Cheap (the trees re-rank when next used: the deciding ones in advance, the rest while
  // growing), so on the tick thread: handing it to the workers cost more than it does.
  for (GraphAvatar& g : avatars) {
    if (g.input_changed || frames_left(library_, *g.avatar) <= 1) {
      g.avatar->set_input(g.input);
      g.input_changed = false;
    }
  }
}

void LookaheadScheduler::grow(std::span<GraphAvatar> avatars, uint32_t tick, Clock::time_point tick_start,
                              TickRecord& record) {
  const Clock::time_point now = Clock::now();
  const size_t n = avatars.size();
  if (n == 0) {
    record.tree_size_min = -1;  // no avatars: not part of the tree figures
    return;
  }
  const double period_ms = 1000.0 / config_.tick_hz;
  const double budget_ms =
      std::clamp(period_ms - ms_between(tick_start, now) - overrun_ms_ - config_.tick_safety_margin_ms, 0.0,
                 config_.lookahead_budget_ms);
  record.budget_ms = static_cast<float>(budget_ms);
  // Shared by need: a thin tree or a decision coming soon asks for more.
  weight_.resize(n);
  expansions_.assign(n, 0);
  double total = 0;
  for (size_t i = 0; i < n; ++i) {
    const LookaheadAvatar& a = *avatars[i].avatar;
    const double thin = std::clamp(1.0 - a.tree().num_nodes() / 64.0, 0.0, 1.0);
    const double soon = std::clamp(1.0 - frames_left(library_, a) / 15.0, 0.0, 1.0);
    weight_[i] = 1.0 + 2.0 * thin + soon;
    total += weight_[i];
  }
  // The threads spend up to budget_ms each, in parallel: the avatars' shares add up to their time.
  const double per_weight_ms = budget_ms * workers_.threads() / total;
  const Clock::time_point end =
      now + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double, std::milli>(budget_ms));
  // The avatars are taken from a different one each tick: those the deadline finds ungrown are
  // not the same every tick.
  const size_t first = (static_cast<size_t>(tick) * 997u) % n;
  // Two pointers captured: the job fits std::function's inline storage (no allocation per tick).
  const struct {
    GraphAvatar* avatars;
    size_t n, first;
    double per_weight_ms;
    Clock::time_point end;
    uint32_t tick;
  } phase{avatars.data(), n, first, per_weight_ms, end, tick};
  workers_.run(static_cast<int>(n), [this, &phase](int claimed, int) {
    const size_t item = (static_cast<size_t>(claimed) + phase.first) % phase.n;
    GraphAvatar& g = phase.avatars[item];
    LookaheadAvatar& a = *g.avatar;
    GrowBudget budget;
    const bool timed = config_.expansions_per_avatar <= 0;
    // Past the deadline an avatar is left as it is: its tree re-ranks under a new command when it
    // is next used (if it decides first, in advance). Re-ranking every late avatar's tree here
    // (about 25 ns a node) ran the stage 10 ms past a 6 ms budget at 1000 avatars.
    if (timed && Clock::now() >= phase.end) return;
    if (timed) {
      double slice_ms = phase.per_weight_ms * weight_[item];
      if (config_.lookahead_avatar_max_ms > 0) slice_ms = std::min(slice_ms, config_.lookahead_avatar_max_ms);
      const auto slice = std::chrono::duration<double, std::milli>(slice_ms);
      budget = GrowBudget::until(std::min(phase.end, Clock::now() + std::chrono::duration_cast<Clock::duration>(slice)));
    } else {
      budget = GrowBudget::expansions(config_.expansions_per_avatar);
    }
    // Command matching measures v_k from where the avatar stands and strategies 1 and 4 re-sort
    // the leaves (about 25 ns a node): at once when the command changes and just before a
    // decision (take_inputs), and otherwise every resort_interval_ticks (1 = every tick, as the
    // lab's replay does every frame), here. On the look-ahead threads, never per packet. The
    // periodic re-sort is dropped, with the growth, when the tick runs late.
    if ((phase.tick + g.id) % static_cast<uint32_t>(config_.resort_interval_ticks) == 0) a.set_input(g.input);
    expansions_[item] = a.grow(budget).expansions;
  });
  record.lookahead_ms = static_cast<float>(ms_between(now, Clock::now()));
  // Past the deadline the workers finish their last leaf: taken off the next budgets.
  if (config_.expansions_per_avatar <= 0 && budget_ms > 0)
    overrun_ms_ = 0.9 * overrun_ms_ + 0.1 * std::max(0.0, record.lookahead_ms - budget_ms);
  int64_t expansions = 0;
  int64_t nodes = 0;
  int min_nodes = INT_MAX;
  for (size_t i = 0; i < n; ++i) {
    expansions += expansions_[i];
    const int size = avatars[i].avatar->tree().num_nodes();
    nodes += size;
    min_nodes = std::min(min_nodes, size);
  }
  record.expansions = expansions;
  record.tree_size_mean = static_cast<float>(static_cast<double>(nodes) / static_cast<double>(n));
  record.tree_size_min = min_nodes;
}

}  // namespace foresight::server

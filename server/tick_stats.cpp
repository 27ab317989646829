#include "tick_stats.hpp"

#include <algorithm>
#include <cmath>

namespace foresight::server {

void TickStats::record(const TickRecord& r, bool overrun) {
  ring_[static_cast<size_t>(next_)] = r;
  next_ = (next_ + 1) % kWindow;
  count_ = std::min(count_ + 1, kWindow);
  ++ticks_;
  if (overrun) ++overruns_;
  for (size_t i = 0; i < kBucketsMs.size(); ++i)
    if (r.tick_ms <= kBucketsMs[i]) ++buckets_[i];
  tick_ms_sum_ += r.tick_ms;
  expansions_total_ += r.expansions;
}

float TickStats::tick_ms_percentile(double p) const {
  if (count_ == 0) return 0.0f;
  std::array<float, kWindow> v;
  for (int i = 0; i < count_; ++i) v[static_cast<size_t>(i)] = ring_[static_cast<size_t>(i)].tick_ms;
  const int k = std::clamp(static_cast<int>(std::ceil(p / 100.0 * count_)) - 1, 0, count_ - 1);
  std::nth_element(v.begin(), v.begin() + k, v.begin() + count_);
  return v[static_cast<size_t>(k)];
}

float TickStats::tick_ms_max() const {
  float m = 0;
  for (int i = 0; i < count_; ++i) m = std::max(m, ring_[static_cast<size_t>(i)].tick_ms);
  return m;
}

TickRecord TickStats::mean() const {
  TickRecord m;
  if (count_ == 0) return m;
  double tick = 0, budget = 0, look = 0, exp = 0, size = 0, players = 0, rec = 0, adv = 0, snd = 0, ter = 0,
         plans = 0;
  int size_min = -1, with_players = 0;
  for (int i = 0; i < count_; ++i) {
    const TickRecord& r = ring_[static_cast<size_t>(i)];
    tick += r.tick_ms, budget += r.budget_ms, look += r.lookahead_ms;
    rec += r.receive_ms, adv += r.advance_ms, snd += r.send_ms;
    exp += static_cast<double>(r.expansions), players += r.players;
    ter += r.terrain_ms, plans += r.terrain_plans;
    if (r.tree_size_min < 0) continue;  // a tick without players
    ++with_players;
    size += r.tree_size_mean;
    size_min = size_min < 0 ? r.tree_size_min : std::min(size_min, r.tree_size_min);
  }
  const double n = count_;
  m.tick_ms = static_cast<float>(tick / n);
  m.budget_ms = static_cast<float>(budget / n);
  m.lookahead_ms = static_cast<float>(look / n);
  m.receive_ms = static_cast<float>(rec / n);
  m.advance_ms = static_cast<float>(adv / n);
  m.send_ms = static_cast<float>(snd / n);
  m.expansions = static_cast<int64_t>(exp / n);
  m.terrain_ms = static_cast<float>(ter / n);
  m.terrain_plans = static_cast<int>(std::lround(plans / n));
  m.tree_size_mean = with_players > 0 ? static_cast<float>(size / with_players) : 0.0f;
  m.tree_size_min = std::max(size_min, 0);
  m.players = static_cast<int>(players / n);
  return m;
}

}  // namespace foresight::server

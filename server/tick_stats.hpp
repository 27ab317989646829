#pragma once
// Per-tick figures the server keeps (docs/SERVER.md): a window of recent ticks for percentiles,
// and totals. Fixed-size ring: recording a tick never allocates.
#include <array>
#include <cstddef>
#include <cstdint>

namespace foresight::server {

struct TickRecord {
  float tick_ms = 0;        ///< Work done in the tick (not the sleep).
  float budget_ms = 0;      ///< Look-ahead budget granted.
  float lookahead_ms = 0;   ///< Look-ahead time spent (tick thread wall-clock).
  float receive_ms = 0;     ///< Draining the socket and expiring sessions.
  float advance_ms = 0;     ///< Playing frames and deciding (reservations included).
  float send_ms = 0;        ///< Snapshots and the contact check.
  float terrain_ms = 0;     ///< Terrain avatars' frames and step plans (part of advance_ms).
  float on_cpu_ms = 0;      ///< The tick thread's time on a CPU during the tick (thread_sched.hpp).
  float waiting_ms = 0;     ///< The tick thread's time runnable but waiting for a CPU.
  int terrain_plans = 0;    ///< Terrain step plans (and turns on the spot) tried this tick.
  int64_t expansions = 0;
  int tree_size_min = 0;    ///< -1: no players this tick.
  float tree_size_mean = 0;
  int players = 0;
};

class TickStats {
 public:
  static constexpr int kWindow = 1024;  ///< About 34 s at 30 Hz.
  /// Upper bounds (ms) of the tick-time histogram's buckets, kept since the start (Prometheus).
  static constexpr std::array<double, 10> kBucketsMs{0.5, 1, 2, 4, 8, 16, 25, 33.3, 50, 100};
  void record(const TickRecord& r, bool overrun);
  /// Percentile (0..100) of tick_ms over the window; 0 when empty.
  float tick_ms_percentile(double p) const;
  float tick_ms_max() const;
  /// The tick recorded last (a zero record before the first).
  const TickRecord& last() const { return ring_[static_cast<size_t>((next_ + kWindow - 1) % kWindow)]; }
  /// Means over the window.
  TickRecord mean() const;
  uint64_t ticks() const { return ticks_; }
  /// Ticks with tick_ms at most kBucketsMs[i], since the start (cumulative, as Prometheus wants).
  const std::array<uint64_t, kBucketsMs.size()>& buckets() const { return buckets_; }
  double tick_ms_sum() const { return tick_ms_sum_; }
  int64_t expansions_total() const { return expansions_total_; }
  uint64_t overruns() const { return overruns_; }

 private:
  std::array<TickRecord, kWindow> ring_{};
  int next_ = 0;
  int count_ = 0;
  uint64_t ticks_ = 0;
  uint64_t overruns_ = 0;
  std::array<uint64_t, kBucketsMs.size()> buckets_{};
  double tick_ms_sum_ = 0;
  int64_t expansions_total_ = 0;
};

}  // namespace foresight::server

#pragma once
// What the admin endpoint shows (admin_http.hpp): the server's figures copied by the tick thread
// at the end of every tick (Server::publish_admin, a few hundred bytes under a mutex) and read by
// the HTTP threads, which never touch the simulation. Rendered as Prometheus text (/metrics) and
// JSON (/status).
#include "server_config.hpp"
#include "tick_stats.hpp"

#include <chrono>
#include <mutex>
#include <string>

namespace foresight::server {

struct ServerCounters;

/// What the server holds in memory (refreshed once a second).
struct MemoryFigures {
  uint64_t resident_bytes = 0;          ///< The process's resident set (/proc/self/statm).
  uint64_t tree_node_bytes = 0;         ///< Every motion tree's node storage (it grows with the work).
  uint64_t snapshot_history_bytes = 0;  ///< The snapshot archive and every client's sent views.
  double heap_trim_ms = 0;              ///< The last release_free_heap() (process_memory.hpp).
};

struct AdminMetrics {
  uint32_t tick = 0;
  double uptime_s = 0;
  int tick_hz = 0, snapshot_hz = 0;
  int players = 0, max_players = 0, fighters = 0, joins_waiting = 0;
  std::string scene, locomotion, strategy;
  double budget_limit_ms = 0, margin_ms = 0;
  bool realtime = false;  ///< The tick's threads run in the real-time class (Server::realtime).
  // Ticks.
  std::array<uint64_t, TickStats::kBucketsMs.size()> tick_buckets{};
  uint64_t ticks = 0, overruns = 0;
  double tick_ms_sum = 0;
  float tick_ms_p50 = 0, tick_ms_p99 = 0, tick_ms_max = 0;
  TickRecord last;  ///< The tick just done.
  TickRecord mean;  ///< Over the stats window (about 34 s).
  int64_t expansions_total = 0;
  // Sessions, packets, bytes (ServerCounters, flattened).
  uint64_t packets_in = 0, bytes_in = 0, packets_out = 0, bytes_out = 0, send_failures = 0;
  uint64_t sessions_opened = 0, sessions_timed_out = 0, sessions_closed = 0, refused = 0, spawn_refusals = 0;
  uint64_t challenges_sent = 0, challenges_capped = 0, joins_deferred = 0;
  uint64_t avatar_contacts = 0, fallbacks = 0, steered_frames = 0, recoveries = 0;
  uint64_t fighter_strikes = 0, fighter_hits = 0;
  uint64_t terrain_steps = 0, terrain_pivots = 0, terrain_refusals = 0;
  uint64_t avatars_sent = 0, avatars_referenced = 0;
  std::array<uint64_t, 16> drops{};  ///< By protocol::DropReason.
  MemoryFigures memory;
  std::chrono::steady_clock::time_point published{};
};

/// The shared copy: the tick thread writes it, HTTP threads read it.
struct AdminState {
  std::mutex mutex;
  AdminMetrics metrics;
  AdminMetrics read() {
    std::lock_guard<std::mutex> lock(mutex);
    return metrics;
  }
};

/// Prometheus text exposition format 0.0.4 (durations in seconds, counters *_total).
std::string admin_metrics_prometheus(const AdminMetrics& m);
/// One JSON object with the same figures (and the configuration in effect).
std::string admin_metrics_json(const AdminMetrics& m);

}  // namespace foresight::server

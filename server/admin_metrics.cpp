#include "admin_metrics.hpp"

#include "protocol/packet.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>

namespace foresight::server {

namespace {

void line(std::string& out, const char* name, const char* type, const char* help, double value) {
  char buf[320];
  std::snprintf(buf, sizeof buf, "# HELP %s %s\n# TYPE %s %s\n%s %.9g\n", name, help, name, type, name, value);
  out += buf;
}

}  // namespace

std::string admin_metrics_prometheus(const AdminMetrics& m) {
  std::string out;
  out.reserve(4096);
  out += "# HELP foresight_tick_seconds Work done per tick (receive, look-ahead, advance, send).\n"
         "# TYPE foresight_tick_seconds histogram\n";
  char buf[160];
  for (size_t i = 0; i < m.tick_buckets.size(); ++i) {
    std::snprintf(buf, sizeof buf, "foresight_tick_seconds_bucket{le=\"%g\"} %llu\n", TickStats::kBucketsMs[i] / 1000.0,
                  static_cast<unsigned long long>(m.tick_buckets[i]));
    out += buf;
  }
  std::snprintf(buf, sizeof buf, "foresight_tick_seconds_bucket{le=\"+Inf\"} %llu\nforesight_tick_seconds_sum %.9g\n"
                "foresight_tick_seconds_count %llu\n", static_cast<unsigned long long>(m.ticks), m.tick_ms_sum / 1000.0,
                static_cast<unsigned long long>(m.ticks));
  out += buf;
  line(out, "foresight_tick_overruns_total", "counter", "Ticks that took longer than the tick period.", static_cast<double>(m.overruns));
  line(out, "foresight_tick_rate_hz", "gauge", "Configured ticks per second.", m.tick_hz);
  line(out, "foresight_players", "gauge", "Connected players (fighters not included).", m.players);
  line(out, "foresight_players_max", "gauge", "Configured player limit.", m.max_players);
  line(out, "foresight_fighters", "gauge", "NPC fighters.", m.fighters);
  line(out, "foresight_joins_waiting", "gauge", "Verified joins queued.", m.joins_waiting);
  line(out, "foresight_lookahead_budget_limit_seconds", "gauge", "Configured look-ahead budget per tick (at most).", m.budget_limit_ms / 1000.0);
  line(out, "foresight_lookahead_budget_seconds", "gauge", "Look-ahead budget granted in the last tick.", m.last.budget_ms / 1000.0);
  line(out, "foresight_lookahead_spent_seconds", "gauge", "Look-ahead time spent in the last tick.", m.last.lookahead_ms / 1000.0);
  line(out, "foresight_lookahead_budget_use_ratio", "gauge", "Look-ahead time spent over budget granted, window mean.",
       m.mean.budget_ms > 0 ? m.mean.lookahead_ms / m.mean.budget_ms : 0.0);
  line(out, "foresight_expansions_total", "counter", "Motion-tree expansions (successor placed, checked, prioritised).",
       static_cast<double>(m.expansions_total));
  line(out, "foresight_tree_size_mean", "gauge", "Mean feasible-motion-tree size (nodes), last tick.", m.last.tree_size_mean);
  line(out, "foresight_tree_size_min", "gauge", "Smallest tree (nodes), last tick (-1: no tree avatar).", m.last.tree_size_min);
  line(out, "foresight_terrain_seconds", "gauge", "Terrain avatars' frames and plans, last tick.", m.last.terrain_ms / 1000.0);
  line(out, "foresight_terrain_steps_total", "counter", "Steps terrain avatars committed.", static_cast<double>(m.terrain_steps));
  line(out, "foresight_terrain_refusals_total", "counter", "Terrain steps refused (the avatar stood).", static_cast<double>(m.terrain_refusals));
  line(out, "foresight_packets_in_total", "counter", "Datagrams received.", static_cast<double>(m.packets_in));
  line(out, "foresight_bytes_in_total", "counter", "Bytes received.", static_cast<double>(m.bytes_in));
  line(out, "foresight_packets_out_total", "counter", "Datagrams sent.", static_cast<double>(m.packets_out));
  line(out, "foresight_bytes_out_total", "counter", "Bytes sent (bandwidth: rate() of it).", static_cast<double>(m.bytes_out));
  line(out, "foresight_send_failures_total", "counter", "Sends the socket refused.", static_cast<double>(m.send_failures));
  line(out, "foresight_snapshot_avatars_total", "counter", "Avatar states sent in snapshots, over all clients.",
       static_cast<double>(m.avatars_sent));
  line(out, "foresight_snapshot_avatars_delta_total", "counter",
       "Of those, delta-coded against a snapshot the client acknowledged.", static_cast<double>(m.avatars_referenced));
  out += "# HELP foresight_packets_dropped_total Datagrams dropped, by reason.\n"
         "# TYPE foresight_packets_dropped_total counter\n";
  for (size_t r = 1; r < static_cast<size_t>(protocol::DropReason::kCount); ++r) {
    std::snprintf(buf, sizeof buf, "foresight_packets_dropped_total{reason=\"%s\"} %llu\n",
                  protocol::drop_reason_name(static_cast<protocol::DropReason>(r)),
                  static_cast<unsigned long long>(m.drops[r]));
    out += buf;
  }
  line(out, "foresight_sessions_opened_total", "counter", "Sessions opened.", static_cast<double>(m.sessions_opened));
  line(out, "foresight_sessions_timed_out_total", "counter", "Sessions dropped for silence.", static_cast<double>(m.sessions_timed_out));
  line(out, "foresight_sessions_closed_total", "counter", "Clean disconnects.", static_cast<double>(m.sessions_closed));
  line(out, "foresight_refused_total", "counter", "Connects refused (version, library, full, cookie).", static_cast<double>(m.refused));
  line(out, "foresight_spawn_refusals_total", "counter", "Joins refused for want of a free place near the spawns.",
       static_cast<double>(m.spawn_refusals));
  line(out, "foresight_challenges_capped_total", "counter", "Connect requests ignored over the per-tick cap.", static_cast<double>(m.challenges_capped));
  line(out, "foresight_avatar_contacts_total", "counter", "Ticks with two avatars' bodies overlapping (must stay 0).", static_cast<double>(m.avatar_contacts));
  line(out, "foresight_fallbacks_total", "counter", "Segment ends with nothing feasible ahead.", static_cast<double>(m.fallbacks));
  line(out, "foresight_steered_frames_total", "counter", "Frames steering mode turned an avatar's playing motion.",
       static_cast<double>(m.steered_frames));
  line(out, "foresight_recoveries_total", "counter", "Times steering mode found an avatar wedged and backed it off.",
       static_cast<double>(m.recoveries));
  line(out, "foresight_fighter_strikes_total", "counter", "Fighters' strikes judged.", static_cast<double>(m.fighter_strikes));
  line(out, "foresight_fighter_hits_total", "counter", "Fighters' strikes that hit.", static_cast<double>(m.fighter_hits));
  line(out, "foresight_uptime_seconds", "gauge", "Since the server started.", m.uptime_s);
  line(out, "foresight_tick_realtime", "gauge",
       "1 when the tick and look-ahead threads run in the real-time class (--realtime-priority, granted).",
       m.realtime ? 1.0 : 0.0);
  line(out, "process_resident_memory_bytes", "gauge", "Resident memory size in bytes.",
       static_cast<double>(m.memory.resident_bytes));
  line(out, "foresight_tree_node_bytes", "gauge", "Node storage of every motion tree (grows with the nodes the budget pays for).",
       static_cast<double>(m.memory.tree_node_bytes));
  line(out, "foresight_snapshot_history_bytes", "gauge",
       "Snapshot history for delta coding: the shared archive and every client's sent views.",
       static_cast<double>(m.memory.snapshot_history_bytes));
  line(out, "foresight_heap_trim_seconds", "gauge",
       "How long the last return of the heap's free pages to the system took (every 5 s).",
       m.memory.heap_trim_ms / 1000.0);
  return out;
}

std::string admin_metrics_json(const AdminMetrics& m) {
  nlohmann::json drops = nlohmann::json::object();
  for (size_t r = 1; r < static_cast<size_t>(protocol::DropReason::kCount); ++r)
    drops[protocol::drop_reason_name(static_cast<protocol::DropReason>(r))] = m.drops[r];
  const nlohmann::json j = {
      {"tick", m.tick},
      {"uptime_s", m.uptime_s},
      {"scene", m.scene},
      {"locomotion", m.locomotion},
      {"players", m.players},
      {"max_players", m.max_players},
      {"fighters", m.fighters},
      {"joins_waiting", m.joins_waiting},
      {"config", {{"tick_hz", m.tick_hz}, {"snapshot_hz", m.snapshot_hz}, {"budget_ms", m.budget_limit_ms},
                  {"margin_ms", m.margin_ms}, {"strategy", m.strategy}, {"realtime", m.realtime}}},
      {"tick_ms", {{"last", m.last.tick_ms}, {"p50", m.tick_ms_p50}, {"p99", m.tick_ms_p99}, {"max", m.tick_ms_max}}},
      {"overruns", m.overruns},
      {"budget_ms", m.last.budget_ms},
      {"lookahead_ms", m.last.lookahead_ms},
      {"budget_use", m.mean.budget_ms > 0 ? m.mean.lookahead_ms / m.mean.budget_ms : 0.0},
      {"expansions_per_tick", m.last.expansions},
      {"tree_size_mean", m.last.tree_size_mean},
      {"tree_size_min", m.last.tree_size_min},
      {"terrain_ms", m.last.terrain_ms},
      {"packets_in", m.packets_in},
      {"bytes_out", m.bytes_out},
      {"snapshot_avatars", m.avatars_sent},
      {"snapshot_avatars_delta", m.avatars_referenced},
      {"dropped", drops},
      {"avatar_contacts", m.avatar_contacts},
      {"fighter_strikes", m.fighter_strikes},
      {"fighter_hits", m.fighter_hits},
      {"memory", {{"resident_bytes", m.memory.resident_bytes},
                  {"tree_node_bytes", m.memory.tree_node_bytes},
                  {"snapshot_history_bytes", m.memory.snapshot_history_bytes}}},
  };
  return j.dump();
}

}  // namespace foresight::server

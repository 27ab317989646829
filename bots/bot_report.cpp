#include "bot_report.hpp"

#include <cmath>
#include <cstdio>

namespace foresight::bots {

namespace {

std::string fixed(double v, int decimals = 1) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.*f", decimals, v);
  return buf;
}

/// Rounds for the JSON: three decimals are plenty for ms and kbps.
double round3(double v) { return std::round(v * 1000.0) / 1000.0; }

}  // namespace

void bot_report_print(const BotReport& r, std::ostream& out) {
  out << "bots: " << r.bots << " (" << r.script << ", scene '" << r.scene << "', "
      << fixed(r.seconds) << " s)\n";
  out << "  connected " << r.connected << ", at the end " << r.connected_at_end << ", refused "
      << r.refused << ", handshake timed out " << r.timed_out << ", server gone " << r.server_gone
      << ", reconnects " << r.reconnects
      << "\n";
  for (const std::string& why : r.refusals) out << "  refusal: " << why << "\n";
  if (!r.error.empty()) out << "  error: " << r.error << "\n";
  out << "  goals reached " << r.goals_reached << ", walked " << fixed(r.walked_m_mean)
      << " m per bot, given up " << r.targets_given_up
      << ", failed plans " << r.plan_failures << "\n";
  for (const std::string& why : r.plan_failure_reasons) out << "  failed plan: " << why << "\n";
  out << "  collisions: " << r.scene_collisions << " with the scene, " << r.avatar_contacts
      << " avatar contacts (" << r.avatars_checked << " avatar states checked, "
      << r.invalid_states << " invalid)\n";
  out << "  rtt ms: p50 " << fixed(r.rtt_ms.percentile(0.5), 2) << ", p99 "
      << fixed(r.rtt_ms.percentile(0.99), 2) << ", max " << fixed(r.rtt_ms.max(), 2) << " ("
      << r.rtt_ms.count() << " samples)\n";
  out << "  snapshot interval ms: p50 " << fixed(r.snapshot_interval_ms.percentile(0.5))
      << ", p99 " << fixed(r.snapshot_interval_ms.percentile(0.99)) << ", max "
      << fixed(r.snapshot_interval_ms.max()) << "\n";
  out << "  per client: down " << fixed(r.down_kbps_p50) << " kbps (p50; max "
      << fixed(r.down_kbps_max) << "), up " << fixed(r.up_kbps_p50) << " kbps (p50)\n";
  out << "  packets: " << r.snapshot_packets << " snapshot parts in, " << r.inputs_sent
      << " inputs out, " << r.drops.total() << " dropped";
  for (size_t i = 1; i < r.drops.by_reason.size(); ++i) {
    if (r.drops.by_reason[i] == 0) continue;
    out << " " << protocol::drop_reason_name(static_cast<protocol::DropReason>(i)) << "="
        << r.drops.by_reason[i];
  }
  if (r.send_failures) out << ", " << r.send_failures << " sends failed";
  out << "\n";
  out << "  bot process: frame work p50 " << fixed(r.frame_ms.percentile(0.5), 2) << " ms, p99 "
      << fixed(r.frame_ms.percentile(0.99), 2) << " ms, " << r.frames_late << " of " << r.frames
      << " frames late\n";
  if (r.has_server_stats) {
    const auto& s = r.server;
    out << "  server: " << s.players << " players, tick " << s.tick_hz << " Hz, tick ms p50 "
        << fixed(s.tick_ms_p50, 2) << " p99 " << fixed(s.tick_ms_p99, 2) << " max "
        << fixed(s.tick_ms_max, 2) << ", overruns " << s.overruns << ", tree size mean "
        << fixed(s.tree_size_mean) << " min " << s.tree_size_min << ", look-ahead "
        << fixed(s.lookahead_ms_mean, 2) << " of " << fixed(s.budget_ms_mean, 2)
        << " ms budget, packets in " << s.packets_in << " dropped " << s.packets_dropped
        << ", avatar contacts " << s.avatar_contacts << "\n";
  } else {
    out << "  server: no ServerStats received\n";
  }
}

nlohmann::json bot_report_json(const BotReport& r) {
  nlohmann::json j;
  j["script"] = r.script;
  j["scene"] = r.scene;
  j["seconds"] = round3(r.seconds);
  j["bots"] = r.bots;
  j["connected"] = r.connected;
  j["connected_at_end"] = r.connected_at_end;
  j["refused"] = r.refused;
  j["timed_out"] = r.timed_out;
  j["server_gone"] = r.server_gone;
  j["reconnects"] = r.reconnects;
  j["churns"] = r.churns;
  j["refusals"] = r.refusals;
  if (!r.error.empty()) j["error"] = r.error;
  j["goals_reached"] = r.goals_reached;
  j["walked_m_mean"] = round3(r.walked_m_mean);
  j["targets_given_up"] = r.targets_given_up;
  j["plan_failures"] = r.plan_failures;
  j["plan_failure_reasons"] = r.plan_failure_reasons;
  j["collisions"] = r.scene_collisions + r.avatar_contacts;
  j["scene_collisions"] = r.scene_collisions;
  j["avatar_contacts"] = r.avatar_contacts;
  j["avatar_states_checked"] = r.avatars_checked;
  j["invalid_avatar_states"] = r.invalid_states;
  j["rtt_samples"] = r.rtt_ms.count();
  j["rtt_ms_p50"] = round3(r.rtt_ms.percentile(0.5));
  j["rtt_ms_p99"] = round3(r.rtt_ms.percentile(0.99));
  j["rtt_ms_max"] = round3(r.rtt_ms.max());
  j["snapshot_interval_ms_p50"] = round3(r.snapshot_interval_ms.percentile(0.5));
  j["snapshot_interval_ms_p99"] = round3(r.snapshot_interval_ms.percentile(0.99));
  j["snapshot_interval_ms_max"] = round3(r.snapshot_interval_ms.max());
  j["down_kbps_per_client_p50"] = round3(r.down_kbps_p50);
  j["down_kbps_per_client_max"] = round3(r.down_kbps_max);
  j["up_kbps_per_client_p50"] = round3(r.up_kbps_p50);
  j["snapshot_packets"] = r.snapshot_packets;
  j["inputs_sent"] = r.inputs_sent;
  j["send_failures"] = r.send_failures;
  j["packets_dropped"] = r.drops.total();
  nlohmann::json by_reason = nlohmann::json::object();
  for (size_t i = 1; i < r.drops.by_reason.size(); ++i) {
    by_reason[protocol::drop_reason_name(static_cast<protocol::DropReason>(i))] = r.drops.by_reason[i];
  }
  j["packets_dropped_by_reason"] = by_reason;
  j["bot_frame_ms_p99"] = round3(r.frame_ms.percentile(0.99));
  j["bot_frames_late"] = r.frames_late;
  if (r.has_server_stats) {
    const auto& s = r.server;
    j["server_tick_ms_p50"] = round3(s.tick_ms_p50);
    j["server_tick_ms_p99"] = round3(s.tick_ms_p99);
    j["server_tick_ms_max"] = round3(s.tick_ms_max);
    j["server_overruns"] = s.overruns;
    j["tree_size_mean"] = round3(s.tree_size_mean);
    j["tree_size_min"] = s.tree_size_min;
    j["server_players"] = s.players;
    j["server_lookahead_ms_mean"] = round3(s.lookahead_ms_mean);
    j["server_budget_ms_mean"] = round3(s.budget_ms_mean);
    j["server_packets_in"] = s.packets_in;
    j["server_packets_dropped"] = s.packets_dropped;
    j["server_avatar_contacts"] = s.avatar_contacts;
  } else {
    for (const char* key : {"server_tick_ms_p50", "server_tick_ms_p99", "server_tick_ms_max",
                            "server_overruns", "tree_size_mean", "tree_size_min", "server_players",
                            "server_lookahead_ms_mean", "server_budget_ms_mean",
                            "server_packets_in", "server_packets_dropped",
                            "server_avatar_contacts"}) {
      j[key] = nullptr;
    }
  }
  return j;
}

}  // namespace foresight::bots

#pragma once
// The outcome of a bot run: what the clients measured, what the collision watch saw, and the
// server's own figures (a ServerStats requested at the end). Printed for people, and as one JSON
// object for scripts (docs/BOTS.md describes every field).
#include "transport/client_connection.hpp"
#include "transport/histogram.hpp"
#include "protocol/packet.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace foresight::bots {

struct BotReport {
  std::string script;
  std::string scene;
  double seconds = 0;  ///< Wall-clock run time, connect to the end.
  int bots = 0;
  int connected = 0;    ///< Bots that were accepted (at any time).
  int connected_at_end = 0;
  int refused = 0;
  int timed_out = 0;    ///< Handshake unanswered.
  int server_gone = 0;  ///< Connected, then the server fell silent or ended the session.
  int reconnects = 0;   ///< Handshakes started again after that (BotFleetConfig::reconnect), or after churn.
  int churns = 0;       ///< Sessions ended on purpose to join again (BotFleetConfig::churn_every_s).
  std::vector<std::string> refusals;  ///< Distinct refusal messages (at most a few).
  std::string error;                  ///< Why the run stopped early (scene or recording missing).

  uint64_t goals_reached = 0;
  double walked_m_mean = 0;  ///< Per accepted bot: its avatar's path length as seen.
  uint64_t targets_given_up = 0;
  uint64_t plan_failures = 0;
  std::vector<std::string> plan_failure_reasons;  ///< Distinct last reasons of bots (at most 3).
  uint64_t scene_collisions = 0;  ///< (tick, avatar) events: the shown pose overlaps the scene.
  uint64_t avatar_contacts = 0;   ///< (tick, pair) events: roots closer than the contact distance.
  uint64_t avatars_checked = 0;   ///< (tick, avatar) states the collision watch examined.
  uint64_t invalid_states = 0;    ///< Avatar states naming what our library does not have.

  protocol::LogHistogram rtt_ms;               ///< All bots' samples.
  protocol::LogHistogram snapshot_interval_ms; ///< All bots' samples.
  protocol::LogHistogram frame_ms;             ///< Work per bot frame (all bots), this process.
  uint64_t frames = 0;
  uint64_t frames_late = 0;  ///< Frames that started more than one period late.
  double down_kbps_p50 = 0, down_kbps_max = 0;  ///< Per connected client, over its session.
  double up_kbps_p50 = 0;
  uint64_t snapshot_packets = 0;
  uint64_t inputs_sent = 0;
  uint64_t send_failures = 0;
  protocol::DropCounters drops;  ///< Datagrams the clients dropped, by reason.

  bool has_server_stats = false;
  protocol::ServerFigures server;
};

/// Several lines for people.
void bot_report_print(const BotReport& report, std::ostream& out);
/// One object; docs/BOTS.md lists the fields. Server figures are null when none arrived.
nlohmann::json bot_report_json(const BotReport& report);

}  // namespace foresight::bots

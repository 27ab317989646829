#pragma once
// What a run of bots does: how many, against which server, driven by which script, for how long.
// Filled by foresight-bots' command line (main.cpp) or directly by in-process tests.
#include "transport/impairment.hpp"
#include "transport/udp_socket.hpp"

#include <cstdint>
#include <string>
#include <string_view>

namespace foresight::bots {

enum class BotScript : uint8_t {
  kReplay,  ///< Open loop: data/recordings/<scene>_eval.json's commands from the moment of Accept.
  kGoals,   ///< Closed loop: a scripted person steers to the scene's goal points, one after another.
  kWander,  ///< Closed loop: random free points a few metres away.
  kDodge,   ///< Wanders, and runs from an NPC fighter that comes close or strikes.
};
const char* bot_script_name(BotScript script);
/// "replay", "goals", "wander"; false for anything else.
bool bot_script_from_name(std::string_view name, BotScript& out);

struct BotFleetConfig {
  protocol::Endpoint server;
  int count = 1;                      ///< Bots, each its own UDP socket and session. [1, 4096]
  BotScript script = BotScript::kGoals;
  double seconds = 10;                ///< Run time from the first connect to the stats request.
  uint64_t seed = 1;                  ///< Goal choices and human behaviour, per bot from this.
  double rate_hz = 30;                ///< Bot frames (and Inputs) per second. [1, 240]
  std::string name_prefix = "bot-";   ///< Client names: prefix + index.
  int connects_per_frame = 20;        ///< Staggers the handshakes of a large fleet.
  int plans_per_frame = 16;           ///< Route plans (A*) per frame over all bots.
  float dodge_radius_m = 2.0f;        ///< dodge: run from a fighter this close (twice as far when it strikes).
  double give_up_target_s = 60;       ///< A target not reached in this time is replaced.
  double stats_wait_s = 1.0;          ///< How long the end waits for the ServerStats answer (at least 3 round trips).
  /// --scene PATH: our copy of the server's scene file (used when its hash is the server's; else,
  /// as when empty and data/scenes/ has no such scene, the server's file is fetched).
  std::string scene_path;
  /// Two avatars whose roots are closer than this count as a contact.
  float contact_distance_m = 0.3f;
  /// A bot whose server went away (shut down, or silent), or whose handshake got no answer in
  /// time, connects again after a back-off that doubles from reconnect_first_s up to
  /// reconnect_max_s (each bot's delay jittered by +-25 %, so a restarted server is not hit by
  /// every bot at once). false: it stays gone. A refusal is final.
  bool reconnect = true;
  /// Churn (soak tests): every churn_every_s one bot (in turn) leaves (Disconnect) and joins again
  /// as a new session half a second later. 0: none.
  double churn_every_s = 0;
  /// Both directions of every bot's link through the impairment layer (each bot its own seed).
  protocol::ImpairmentConfig impairment;
  double reconnect_first_s = 0.5;
  double reconnect_max_s = 8.0;
};

}  // namespace foresight::bots

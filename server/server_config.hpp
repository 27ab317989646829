#pragma once
// Every tunable of the server, with its default. The command line (main.cpp) sets them;
// docs/SERVER.md explains each.
#include "library_build/library_source.hpp"
#include "lookahead/strategy.hpp"

#include <cstdint>
#include <string>

namespace foresight::server {

/// How players' avatars move.
enum class Locomotion : std::uint8_t {
  kAuto,     ///< Terrain when the scene has a height field or step blocks, else the graph.
  kGraph,    ///< The feasible motion tree over the motion graph (issue 3).
  kTerrain,  ///< The footstep and upper-body planners (issue 7, docs/TERRAIN.md).
};

struct ServerConfig {
  std::string scene = "maze";      ///< data/scenes/<scene>.json
  std::string bind_address = "0.0.0.0";
  uint16_t port = 7777;            ///< 0: any free port (tests).
  int tick_hz = 30;
  int snapshot_hz = 20;
  int max_players = 512;
  double session_timeout_s = 5.0;  ///< A client silent this long is dropped, its avatar removed.
  /// Look-ahead budget per tick: what the tick period leaves after the rest of the tick, minus the
  /// safety margin, at most this much (ms of wall-clock per tick, across all threads).
  double lookahead_budget_ms = 8.0;
  /// At most this much of it for one avatar in one tick (0: no cap beyond its share by need).
  double lookahead_avatar_max_ms = 0.0;
  double tick_safety_margin_ms = 6.0;
  /// Deterministic mode (tests, experiments): > 0 grows every tree by exactly this many
  /// expansions per tick instead of a time budget; 0 uses time.
  int64_t expansions_per_avatar = 0;
  int threads = 0;                 ///< Look-ahead threads, the tick thread included (0: one per core).
  /// > 0: run() puts the tick thread and the look-ahead workers in the real-time FIFO class at
  /// this priority (1-99; thread_priority.hpp), so that a woken tick thread never waits for a
  /// CPU behind other programs; refused without CAP_SYS_NICE or RLIMIT_RTPRIO (logged, the
  /// server then ticks at normal priority). 0: the normal class.
  int realtime_priority = 0;
  double status_every_s = 10.0;    ///< A status line in the log this often (0: never).
  Strategy strategy = Strategy::kCommand;
  int tree_max_nodes = 8192;       ///< Per avatar (56 B per node), at most kMaxTreeNodes.
  /// Trees are re-prioritised when the command changes, before each decision, and at least every
  /// this many ticks (1: every tick, the lab's replay semantics).
  int resort_interval_ticks = 4;
  int tree_max_depth = 8;
  /// Steering mode of the avatars' look-ahead (MotionTreeConfig::steer_rad_per_s, in deg/s; 0:
  /// off, the paper's controller). On by default at the lab's responsive controller's 540
  /// (docs/LAB.md): clients show it through the pose stage, which keeps feet planted.
  float steer_deg_per_s = 540.0f;
  /// Per session: more packets than this per second are dropped (counted); input commands come
  /// at most at the client's frame rate.
  int max_packets_per_s = 120;
  /// Challenges answered per tick at most (a connect flood cannot eat the tick).
  int max_challenges_per_tick = 256;
  /// New players admitted per tick at most (creating an avatar and finding it a free spawn place
  /// costs about a millisecond); verified joins beyond it wait in a queue, first come first served.
  int max_joins_per_tick = 4;
  MotionSource motions;            ///< Default library, or --motions DIR.
  /// Interest management (interest.hpp): avatars within this of a client's own go into its every
  /// snapshot, the others every far_every-th (0: never). 0 m: everyone in every snapshot.
  float interest_radius_m = 0.0f;
  int far_every = 4;
  /// Beyond this (when larger than interest_radius_m) an avatar is not sent at all; 0: no limit.
  float far_radius_m = 0.0f;
  /// Agones SDK sidecar (agones_sdk.hpp): -1 off; 0 its REST port from AGONES_SDK_HTTP_PORT (else
  /// 9358); > 0 that port.
  int agones_sdk_port = -1;
  double agones_health_s = 2.0;  ///< Between health pings.
  // The admin endpoint (admin_http.hpp): loopback unless told otherwise, behind a token.
  std::string admin_bind = "127.0.0.1";
  int admin_port = 7778;           ///< -1: no endpoint; 0: any free port.
  std::string admin_token;         ///< Empty: a random one, printed at start.
  Locomotion locomotion = Locomotion::kAuto;
  /// NPC fighters (issue 6): -1 = one per NPC spawn of the scene; N >= 0 = that many (beyond the
  /// scene's NPC spawns they start at its player spawns: load tests).
  int fighters = -1;
  bool fighters_auto_attack = true;  ///< Own policy; false: they strike only when ordered.
  double fighter_cooldown_s = 2.5;   ///< Between two strikes of the own policy.
  int fighter_morphology = -1;      ///< -1: fighters cycle through the five morphologies; 0-4: all this one.
  float fighter_hit_radius_m = 0.15f;  ///< A strike hits when the effector comes this close to the head.
  std::string fighter_strikes;       ///< Extra BVH folder of strikes for the fighters' database.
  std::string fighter_strikes_sidecar;  ///< Its annotations (empty: the folder's strikes.json, else detection).
  std::string fighter_cache_dir;     ///< Where pose clusters are cached (empty: computed at start).
};

}  // namespace foresight::server

#pragma once
// The authoritative server (docs/SERVER.md). One UDP socket, a fixed tick:
//
//   receive   drain the socket: handshakes, inputs, heartbeats, stats and tree requests; every
//             datagram verified first, bad ones dropped and counted by reason
//   expire    drop sessions silent for session_timeout_s (their avatars go with them)
//   advance   play each avatar's clip frames due this tick; at a segment end it takes its tree's
//             best child that keeps clear of the other avatars' committed motion (reservations).
//             Terrain avatars (Locomotion::kTerrain) play one frame and plan their next step
//             where one ends (server_terrain.cpp)
//   look      grow every avatar's feasible motion tree within the tick's look-ahead budget,
//             shared by need, on `threads` cores
//   send      snapshots at snapshot_hz
//
// run_tick() does one tick and is what tests call (with a fake clock they stay deterministic in
// expansion-budget mode); run() loops it at tick_hz until stop() is called.
#include "lookahead/lookahead_avatar.hpp"
#include "lookahead/reservations.hpp"
#include "terrain/terrain_avatar.hpp"
#include "admin_commands.hpp"
#include "agones_sdk.hpp"
#include "admin_http.hpp"
#include "fighters/fighter_assets.hpp"
#include "fighters/fighter_npc.hpp"
#include "interest.hpp"
#include "lookahead_workers.hpp"
#include "protocol/avatar_delta.hpp"
#include "protocol/sent_views.hpp"
#include "snapshot_builder.hpp"
#include "transport/cookie.hpp"
#include "protocol/packet.hpp"
#include "transport/session_crypto.hpp"
#include "transport/udp_socket.hpp"
#include "server_config.hpp"
#include "tick_stats.hpp"
#include "tree_summary.hpp"
#include "world/body_volume.hpp"
#include "world/collision_world.hpp"
#include "world/scene.hpp"

#include <atomic>
#include <chrono>
#include <deque>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

namespace foresight::server {

using Clock = std::chrono::steady_clock;

/// Counters an operator (and the tests) read.
struct ServerCounters {
  uint64_t packets_in = 0;
  uint64_t bytes_in = 0;
  uint64_t packets_out = 0;
  uint64_t bytes_out = 0;
  uint64_t send_failures = 0;
  uint64_t challenges_sent = 0;
  uint64_t challenges_capped = 0;   ///< Connect requests ignored: over max_challenges_per_tick.
  uint64_t sessions_opened = 0;
  uint64_t joins_deferred = 0;      ///< Verified joins that had to queue (max_joins_per_tick).
  uint64_t sessions_timed_out = 0;
  uint64_t sessions_closed = 0;     ///< Clean disconnects.
  uint64_t refused = 0;             ///< Refuse messages sent (library, version, full, cookie).
  uint64_t spawn_refusals = 0;      ///< Of those, joins with no free place near the spawns.
  uint64_t scene_parts_sent = 0;    ///< ScenePart answers to clients fetching the scene file.
  uint64_t avatar_contacts = 0;     ///< Ticks with two avatars' bodies overlapping (must stay 0).
  uint64_t fallbacks = 0;
  uint64_t steered_frames = 0;      ///< Frames steering mode turned an avatar's playing motion.
  uint64_t recoveries = 0;          ///< Times steering mode found an avatar wedged and backed it off.
  uint64_t fighter_strikes = 0;     ///< Strikes judged.
  uint64_t fighter_hits = 0;
  uint64_t fighter_strike_failures = 0;  ///< Decided but not startable (logged).
  uint64_t fighter_route_failures = 0;   ///< No route around the walls to a fighter's target.
  uint64_t terrain_steps = 0;     ///< Steps terrain avatars committed.
  uint64_t terrain_pivots = 0;    ///< Turns on the spot.
  uint64_t terrain_refusals = 0;  ///< Plans that failed or were vetoed (the avatar stood).
  uint64_t avatars_sent = 0;        ///< Avatar states in snapshots, over all clients.
  uint64_t avatars_referenced = 0;  ///< Of those, delta-coded against an acknowledged snapshot.
  protocol::DropCounters drops;
};

class Server {
 public:
  Server();
  ~Server();
  /// Loads the scene and the motion library, binds the socket. False with a reason.
  bool start(const ServerConfig& config, std::string& error);
  uint16_t port() const { return socket_.local_port(); }

  /// One tick at time `now`.
  void run_tick(Clock::time_point now);
  /// Ticks at tick_hz until stop() (from any thread or a signal handler).
  void run();
  void stop() { stop_requested_.store(true); }
  /// Graceful shutdown: tells every client (Refuse ShuttingDown, sent twice against a loss) and
  /// closes its session. run() does it when stopped; a client then knows at once instead of
  /// after its timeout, and bots reconnect with back-off.
  void close_sessions();

  /// The configuration in effect (with the admin's run-time changes: set budget-ms, ...).
  const ServerConfig& config() const { return config_; }
  const MotionLibrary& library() const { return library_; }
  const Scene& scene() const { return scene_; }
  const ServerCounters& counters() const { return counters_; }
  const TickStats& tick_stats() const { return stats_; }
  int num_players() const;
  uint32_t tick() const { return tick_; }

  /// A player's avatar, for tests and tools (nullptr if none with that id, or a terrain avatar).
  const LookaheadAvatar* avatar(uint32_t avatar_id) const;
  /// A terrain player's avatar (nullptr if none with that id on terrain).
  const terrain::TerrainAvatar* terrain_avatar(uint32_t avatar_id) const;
  /// Players walk by the terrain planners (ServerConfig::locomotion, resolved at start).
  bool terrain_mode() const { return terrain_mode_; }
  /// Avatar ids in play (players and fighters).
  std::vector<uint32_t> avatar_ids() const;
  /// NPC fighters' avatar ids, in spawn order.
  std::vector<uint32_t> fighter_ids() const;
  int num_fighters() const { return num_fighters_; }
  /// Runs one supervisor command (admin_commands.hpp) now and returns the reply. Tick thread only.
  AdminReply admin_command(const std::string& line);
  /// Where any thread (the console) queues commands; they run at the start of the next tick and
  /// their replies go to stdout. Shared, so a console thread can outlive the server safely.
  std::shared_ptr<AdminQueue> admin_queue() const { return admin_queue_; }
  /// The admin endpoint's TCP port, or -1 when it is not running.
  int admin_port() const { return admin_ ? admin_->port() : -1; }
  const std::string& admin_token() const { return admin_token_; }
  /// The Agones SDK client (--agones), or nullptr.
  const AgonesSdk* agones() const { return agones_.get(); }
  /// The fighters' shared data (database, morphologies), or nullptr without fighters.
  const FighterAssets* fighter_assets() const { return fighter_assets_.get(); }
  /// A fighter's body as last animated (what the next snapshot sends), or nullptr.
  const PoseBuffers* fighter_pose(uint32_t avatar_id) const;
  /// A supervisor's order to a fighter against its current target (ignored while it strikes).
  /// False: no such fighter, or it has no target (no player).
  bool order_fighter(uint32_t avatar_id, StrikeOrder order);
  /// The most recent strike outcomes, oldest first (at most kStrikeEventsKept).
  const std::deque<StrikeEvent>& strike_events() const { return strike_events_; }
  static constexpr size_t kStrikeEventsKept = 64;

 private:
  struct Player;
  struct PendingJoin {
    protocol::Endpoint endpoint;
    uint64_t key = 0;
    std::string name;
    protocol::SessionKey client_key{};
  };

  void receive(Clock::time_point now);
  void handle(const protocol::Endpoint& from, const wire::Packet& packet, size_t bytes,
              Clock::time_point now);
  void on_connect_request(const protocol::Endpoint& from, const wire::ConnectRequest& m, size_t bytes,
                          Clock::time_point now);
  void on_connect_response(const protocol::Endpoint& from, const wire::ConnectResponse& m,
                           Clock::time_point now);
  void on_input(Player& p, const wire::Input& m);
  void admit_joins(Clock::time_point now);
  void admit(const PendingJoin& join, Clock::time_point now);
  void send_refuse(const protocol::Endpoint& to, wire::RefuseReason reason, const std::string& message);
  void send_accept(const Player& p);
  void send_stats(Player& p);
  /// Sends `inner` (a whole packet) to a player inside its session's Sealed wrapping.
  void send_sealed(Player& p, std::span<const uint8_t> inner);
  void handle_session(Player& p, const wire::Packet& packet, Clock::time_point now);
  void send_tree(Player& p);
  void send_scene_part(Player& p, uint32_t offset);  ///< One ScenePart from `offset` (SceneRequest).
  void expire(Clock::time_point now);
  void remove_player(size_t index);
  void advance(TickRecord& record);
  void grow_trees(Clock::time_point tick_start, Clock::time_point now, TickRecord& record);
  void send_snapshots(Clock::time_point now);
  void check_contacts();
  // NPC fighters (server_fighters.cpp).
  bool spawn_fighters(std::string& error);
  void think_fighters(Clock::time_point now);
  /// Where fighter `npc` at `from` should walk to reach `to` (the target, or a route corner).
  vec2 fighter_way(FighterNpc& npc, vec2 from, vec2 to, double now_s);
  void animate_fighters(int64_t frames_due);
  void collect_fighter_poses();
  void judge_strike(Player& fighter, const StrikeFrame& frame);
  vec3 head_position(const LookaheadAvatar& avatar);
  // Terrain avatars (server_terrain.cpp).
  bool terrain_place_free(const Placement& place) const;
  void advance_terrain(TickRecord& record);
  void collect_terrain_body(const Player& p);
  MemoryFigures memory_figures() const;
  void log_status() const;
  void publish_admin(Clock::time_point now);
  AdminReply admin_set(const std::string& key, const std::string& value);
  /// Where avatars may stand near `around` (the scene allows it; other avatars not considered),
  /// nearest first, at most `max_places`.
  std::vector<Placement> free_places_around(std::span<const Placement> around, size_t max_places) const;
  bool place_is_free_now(const Placement& p) const;  ///< No avatar's reservation (or body) there.
  bool plan_spawn_places(std::string& error);          ///< spawn_places_, warnings for spawns that do not fit.
  bool find_spawn(Placement& out) const;               ///< The first of spawn_places_ free now.
  bool find_free_place(std::span<const Placement> around, Placement& out) const;
  Player* find_player(const protocol::Endpoint& from);
  void send(std::span<const uint8_t> bytes, const protocol::Endpoint& to);

  ServerConfig config_;
  MotionLibrary library_;
  Scene scene_;
  CollisionWorld world_;
  MotionTreeConfig tree_config_;
  int spawn_segment_ = -1;
  /// Places near the scene's spawns where the standing body fits the scene, nearest first: a
  /// join only checks them against the other avatars (bounded work per join, however full).
  static constexpr size_t kMaxSpawnPlaces = 8192;
  float fighter_route_clearance_m_ = 0.35f;  ///< Fighters' routes: the library's walker (spawn_fighters).
  float fighter_route_height_m_ = 1.85f;
  std::vector<Placement> spawn_places_;
  std::string scene_file_;   ///< The scene file's bytes, sent to clients that lack them.
  uint64_t scene_hash_ = 0;  ///< protocol::scene_file_hash(scene_file_), in every Accept.
  int head_joint_ = -1;  ///< The library skeleton's head (fighters aim at it).
  Pose head_pose_;       ///< Scratch for head_position.
  std::vector<vec3> head_global_pos_;
  std::vector<quat> head_global_rot_;

  protocol::UdpSocket socket_;
  protocol::CookieJar cookies_;
  protocol::PacketWriter writer_;
  protocol::PacketWriter seal_writer_;  ///< The Sealed wrapping around what writer_ holds.
  std::vector<uint8_t> receive_buffer_;
  std::vector<std::unique_ptr<Player>> players_;
  std::unordered_map<uint64_t, Player*> by_endpoint_;  ///< endpoint_key -> player
  std::vector<std::unique_ptr<Player>> retired_;        ///< Removed, memory not yet released.
  /// Cookie-verified joins waiting their turn (at most max_players - players long).
  std::deque<PendingJoin> join_queue_;
  Reservations reservations_;
  std::unique_ptr<LookaheadWorkers> workers_;
  std::vector<wire::AvatarState> snapshot_states_;  ///< Reused every snapshot.
  // Fighters' poses and strike events for the snapshot being sent (server_fighters.cpp); reused.
  std::vector<FighterPoseOut> fighter_poses_;
  std::vector<uint32_t> fighter_rotations_;
  std::vector<wire::StrikeEventState> snapshot_events_;
  std::vector<wire::TerrainBody> snapshot_terrain_;  ///< Terrain avatars' bodies, in snapshot_states_ order.
  std::vector<uint32_t> terrain_before_;             ///< Per snapshot avatar (and one past): bodies before it.
  std::vector<vec2> snapshot_positions_;             ///< Per snapshot avatar: where it stands (interest).
  InterestGrid interest_grid_;
  std::vector<uint32_t> by_id_;                      ///< players_ indices by avatar id (snapshot order).
  std::vector<BodyVolume> contact_bodies_;           ///< check_contacts: this frame's bodies (reused).
  /// The avatars of the last 64 snapshots, once for every client (sent_views.hpp).
  protocol::SnapshotArchive snapshot_archive_;
  std::vector<SnapshotReceiver> snapshot_receivers_;                ///< This snapshot's clients (reused).
  std::vector<std::unique_ptr<SnapshotBuilder>> snapshot_builders_;  ///< One per look-ahead worker.
  bool terrain_mode_ = false;
  terrain::TerrainAvatarConfig terrain_config_;
  std::vector<terrain::TerrainNeighbour> terrain_neighbours_;  ///< Reused per planning avatar.
  std::vector<Player*> tree_players_;                ///< Players with a motion tree, this tick.
  TreeSummaryWriter tree_summary_;                  ///< Reused for every TreeRequest.
  std::vector<double> grow_weight_;                 ///< Per player, reused.
  std::vector<int64_t> grow_expansions_;            ///< Per player, this tick.
  std::vector<Clock::time_point> grow_deadline_;    ///< Per worker.

  Clock::time_point started_{};
  uint32_t tick_ = 0;
  uint32_t next_session_ = 1;
  uint32_t next_avatar_ = 1;
  int num_fighters_ = 0;
  std::unique_ptr<FighterAssets> fighter_assets_;
  std::unique_ptr<FighterRetriever> fighter_retriever_;
  std::deque<StrikeEvent> strike_events_;
  std::shared_ptr<AdminQueue> admin_queue_ = std::make_shared<AdminQueue>();
  std::vector<AdminRequest> admin_requests_;
  std::shared_ptr<AdminState> admin_state_;
  std::unique_ptr<AdminEndpoint> admin_;  ///< Last member: its threads stop before the rest goes.
  std::atomic<int64_t> last_tick_ns_{0};   ///< Steady clock of the latest tick (the Agones health thread reads it).
  std::unique_ptr<AgonesSdk> agones_;      ///< After last_tick_ns_: its thread reads it until it stops.
  std::string admin_token_;
  uint32_t next_strike_event_ = 1;
  double snapshot_accumulator_ = 0;
  uint32_t snapshot_tick_ = 0;
  int challenges_this_tick_ = 0;
  double tail_ms_estimate_ = 0;
  uint32_t next_overrun_log_tick_ = 0;  ///< Recent advance + send time (EMA), kept out of the budget.
  ServerCounters counters_;
  TickStats stats_;
  std::atomic<bool> stop_requested_{false};
};

}  // namespace foresight::server

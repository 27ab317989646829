#pragma once
// The authoritative server (docs/SERVER.md). One UDP socket, a fixed tick. run_tick() is the
// pipeline, read top to bottom in server.cpp; each stage loops over its own data:
//
//   1 receive    the session table drains the socket: handshakes, sealed session messages (a
//                player's held command, heartbeats, stats, tree and scene requests), bad datagrams
//                dropped and counted by reason; queued joins get an avatar; silent sessions end
//   2 commands   the supervisor's and the admin endpoint's commands queued since the last tick
//   3 think      NPC fighters perceive the nearest player and set their command
//   4 commands   each motion-graph avatar's tree takes its player's new command (re-ranked from
//                where the avatar stands when next used) (lookahead_scheduler.hpp)
//   5 advance    each avatar plays the clip frames due; at a segment end it takes its tree's best
//                child that keeps clear of the others' committed motion (reservations); fighters
//                play their strikes; terrain avatars play a frame and plan a step where one ends
//   6 send       at snapshot_hz: the avatars in id order gathered once, then each client's view
//                built, delta-coded, sealed and sent on the workers (snapshot_builder.hpp); the
//                contact check
//   7 look       every motion-graph avatar's feasible motion tree grows until the tick's
//                deadline, shared by need, on `threads` cores, for the decisions to come: last,
//                so that a slow stage before it shortens the growth, not the tick
//   8 finish     tick figures, the overrun line, the admin endpoint's figures, the status line
//                (the heap's free pages go back to the system every 5 s on a thread of its own,
//                HeapTrimmer in process_memory.hpp, never in a tick)
//
// Avatars live in one table per kind (avatars.hpp) addressed by generation-counted handles;
// sessions in the session table (session_table.hpp). run() loops run_tick at tick_hz until
// stop(); tests call run_tick with their own clock (deterministic in expansion-budget mode).
#include "admin_commands.hpp"
#include "admin_http.hpp"
#include "agones_sdk.hpp"
#include "avatars.hpp"
#include "clock.hpp"
#include "fighters/fighter_assets.hpp"
#include "interest.hpp"
#include "lookahead/reservations.hpp"
#include "lookahead_scheduler.hpp"
#include "lookahead_workers.hpp"
#include "process_memory.hpp"
#include "protocol/sent_views.hpp"
#include "server_config.hpp"
#include "server_counters.hpp"
#include "session_table.hpp"
#include "snapshot_builder.hpp"
#include "tick_stats.hpp"
#include "tree_summary.hpp"
#include "world/body_volume.hpp"
#include "world/collision_world.hpp"
#include "world/scene.hpp"

#include <atomic>
#include <chrono>
#include <deque>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace foresight::server {

class Server : private SessionEvents {
 public:
  Server();
  ~Server();
  /// Loads the scene and the motion library, binds the socket. False with a reason.
  bool start(const ServerConfig& config, std::string& error);
  uint16_t port() const { return sessions_.port(); }

  /// One tick at time `now`.
  void run_tick(Clock::time_point now);
  /// Ticks at tick_hz until stop() (from any thread or a signal handler).
  void run();
  void stop() { stop_requested_.store(true); }
  /// run() put the tick thread and the look-ahead workers in the real-time class
  /// (ServerConfig::realtime_priority, and the system allowed it).
  bool realtime() const { return realtime_.load(); }
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
  uint32_t tick() const { return tick_; }
  int num_players() const { return static_cast<int>(sessions_.size()); }

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
  // Stages of run_tick (server.cpp), in order.
  void run_admin_commands();
  /// run()'s thread and the workers into the real-time class, if configured (logged either way).
  void enter_realtime();
  void think_fighters();                      // server_fighters.cpp
  void advance(TickRecord& record);
  void animate_fighters(int64_t frames_due);  // server_fighters.cpp
  void advance_terrain(TickRecord& record);   // server_terrain.cpp
  void send_snapshots(Clock::time_point now);
  /// Snapshots the client of `avatar_id` is due by `tick` (it is served when this moves on).
  uint64_t snapshots_by(uint32_t tick, uint32_t avatar_id) const;
  void check_contacts();
  void finish_tick(TickRecord& record, const StageTimer& timer);

  // What a session's join, messages and end mean in the game (SessionEvents).
  bool on_join(Session& s, Clock::time_point now, wire::RefuseReason& reason, std::string& why) override;
  void on_message(Session& s, const wire::Packet& message) override;
  void on_leave(const Session& s) override;
  void on_input(Session& s, const wire::Input& m);
  void send_stats(Session& s);
  void send_tree(Session& s);
  void send_scene_part(Session& s, uint32_t offset);  ///< One ScenePart from `offset` (SceneRequest).

  /// The avatar with this id by kind, or nullptr (a binary search of the roster).
  GraphAvatar* graph_avatar(uint32_t id);
  const GraphAvatar* graph_avatar(uint32_t id) const;
  /// The fighter whose body has this id, or nullptr.
  Fighter* fighter(uint32_t id);
  const Fighter* fighter(uint32_t id) const;
  /// A player's (not a fighter's) motion-graph avatar, or nullptr.
  const GraphAvatar* player_avatar(uint32_t id) const;

  // NPC fighters (server_fighters.cpp).
  bool spawn_fighters(std::string& error);
  /// Where fighter `npc` at `from` should walk to reach `to` (the target, or a route corner).
  vec2 fighter_way(FighterNpc& npc, vec2 from, vec2 to, double now_s);
  void collect_fighter_poses();
  void judge_strike(const Fighter& fighter, const StrikeFrame& frame);
  vec3 head_position(const LookaheadAvatar& avatar);
  // Terrain avatars (server_terrain.cpp).
  bool terrain_place_free(const Placement& place) const;
  void collect_terrain_body(const TerrainWalker& walker);
  MemoryFigures memory_figures() const;
  void log_status() const;
  void publish_admin(Clock::time_point now);
  AdminReply admin_set(const std::string& key, const std::string& value);
  /// Where avatars may stand near `around` (the scene allows it; other avatars not considered),
  /// nearest first, at most `max_places`.
  std::vector<Placement> free_places_around(std::span<const Placement> around, size_t max_places) const;
  bool place_is_free_now(const Placement& p) const;  ///< No avatar's reservation (or body) there.
  bool plan_spawn_places(std::string& error);          ///< spawn_places_, warnings for spawns that do not fit.
  /// The first of spawn_places_ free now, passing over places found taken in the last
  /// kSpawnRecheckTicks (and looking at those only when no other is free).
  bool find_spawn(Placement& out);
  bool find_free_place(std::span<const Placement> around, Placement& out) const;

  ServerCounters counters_;  ///< First: the session table counts into it.
  ServerConfig config_;
  MotionLibrary library_;
  Scene scene_;
  CollisionWorld world_;
  /// Every avatar's motion-tree nodes, in chunks (before the avatars: they give them back).
  MotionNodePool node_pool_;
  /// The heap's free pages go back to the system every 5 s, off the tick (process_memory.hpp).
  HeapTrimmer heap_trimmer_{std::chrono::seconds(5)};
  MotionTreeConfig tree_config_;
  int spawn_segment_ = -1;
  /// Places near the scene's spawns where the standing body fits the scene, nearest first: a
  /// join only checks them against the other avatars (bounded work per join, however full).
  static constexpr size_t kMaxSpawnPlaces = 8192;
  float fighter_route_clearance_m_ = 0.35f;  ///< Fighters' routes: the library's walker (spawn_fighters).
  float fighter_route_height_m_ = 1.85f;
  std::vector<Placement> spawn_places_;
  /// Per spawn place, the tick it was last found taken or given out (0: never). In a burst of
  /// joins the places given out in the last ticks are still taken, and checking each of them
  /// again (the spawn segment against the reservations) made a join cost O(players): 13 % of the
  /// server's time while 1000 bots joined, 12-15 ms receive stages.
  std::vector<uint32_t> spawn_place_taken_at_;
  static constexpr uint32_t kSpawnRecheckTicks = 15;
  std::string scene_file_;   ///< The scene file's bytes, sent to clients that lack them.
  uint64_t scene_hash_ = 0;  ///< protocol::scene_file_hash(scene_file_), in every Accept.
  int head_joint_ = -1;  ///< The library skeleton's head (fighters aim at it).
  Pose head_pose_;       ///< Scratch for head_position.
  std::vector<vec3> head_global_pos_;
  std::vector<quat> head_global_rot_;

  SessionTable sessions_{counters_};
  std::unique_ptr<LookaheadWorkers> workers_;
  std::unique_ptr<LookaheadScheduler> scheduler_;
  // The avatars: one table per kind, and all of them in id order.
  HandleTable<GraphAvatar> graph_avatars_;
  HandleTable<TerrainWalker> terrain_walkers_;
  HandleTable<Fighter> fighters_;
  Roster roster_;
  Reservations reservations_;
  std::vector<wire::AvatarState> snapshot_states_;  ///< Reused every snapshot.
  // Fighters' poses and strike events for the snapshot being sent (server_fighters.cpp); reused.
  std::vector<FighterPoseOut> fighter_poses_;
  std::vector<uint32_t> fighter_rotations_;
  std::vector<wire::StrikeEventState> snapshot_events_;
  std::vector<wire::TerrainBody> snapshot_terrain_;  ///< Terrain avatars' bodies, in snapshot_states_ order.
  std::vector<uint32_t> terrain_before_;             ///< Per snapshot avatar (and one past): bodies before it.
  std::vector<vec2> snapshot_positions_;             ///< Per snapshot avatar: where it stands (interest).
  InterestGrid interest_grid_;
  std::vector<BodyVolume> contact_bodies_;           ///< check_contacts: this frame's bodies (reused).
  /// The avatars of the last snapshots gathered, once for every client (sent_views.hpp), as many
  /// as a client's references reach over at its snapshot rate.
  protocol::SnapshotArchive snapshot_archive_;
  std::vector<SnapshotReceiver> snapshot_receivers_;                ///< This snapshot's clients (reused).
  std::vector<std::unique_ptr<SnapshotBuilder>> snapshot_builders_;  ///< One per look-ahead worker.
  bool terrain_mode_ = false;
  terrain::TerrainAvatarConfig terrain_config_;
  std::vector<terrain::TerrainNeighbour> terrain_neighbours_;  ///< Reused per planning avatar.
  TreeSummaryWriter tree_summary_;                  ///< Reused for every TreeRequest.

  Clock::time_point started_{};
  uint32_t tick_ = 0;
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
  uint32_t snapshots_gathered_ = 0;  ///< Ticks that gathered a snapshot: the number of the newest.
  uint32_t next_overrun_log_tick_ = 0;
  TickStats stats_;
  std::atomic<bool> stop_requested_{false};
  std::atomic<bool> realtime_{false};
};

}  // namespace foresight::server

#include "server.hpp"

#include "io/text_file.hpp"
#include "library/body_fit.hpp"
#include "process_memory.hpp"

#include "protocol/input_packet.hpp"
#include "protocol/quantize.hpp"
#include "thread_priority.hpp"
#include "thread_sched.hpp"
#include "transport/scene_transfer.hpp"
#include "world/data_paths.hpp"
#include "world/scene_load.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <thread>

#include <pthread.h>

namespace foresight::server {

namespace {

// Frames of clip time due at the end of tick `tick` (clips play in real time at `fps` whatever the
// tick rate).
int64_t frames_due(uint32_t tick, double fps, int tick_hz) {
  return static_cast<int64_t>(std::floor(static_cast<double>(tick) * fps / tick_hz + 1e-9));
}

}  // namespace

Server::Server() = default;
Server::~Server() = default;

bool Server::start(const ServerConfig& config, std::string& error) {
  config_ = config;
  config_.tick_hz = std::clamp(config_.tick_hz, 1, 240);
  config_.snapshot_hz = std::clamp(config_.snapshot_hz, 1, config_.tick_hz);
  if (config_.threads <= 0) config_.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  config_.threads = std::clamp(config_.threads, 1, 64);
  config_.resort_interval_ticks = std::max(config_.resort_interval_ticks, 1);
  if (!scene_world_load(config_.scene, scene_, world_, error)) return false;
  // The file's bytes as loaded: their hash goes in every Accept, and they are sent to clients
  // that lack them (docs/PROTOCOL.md, "Scenes").
  if (!text_file_read(scene_path(config_.scene), kMaxSceneFileBytes, scene_file_, error)) return false;
  if (scene_file_.size() > protocol::kMaxFetchedSceneBytes)
    std::fprintf(stderr, "foresight-server: the scene file is %zu bytes: clients fetch at most %u, so they must have it\n",
                 scene_file_.size(), protocol::kMaxFetchedSceneBytes);
  scene_hash_ = protocol::scene_file_hash(scene_file_);
  if (!motion_library_load(config_.motions, library_, error)) return false;
  spawn_segment_ = find_spawn_segment(library_);
  if (spawn_segment_ < 0) {
    error = "motion library '" + library_.name + "' has no segment to spawn avatars in";
    return false;
  }
  tree_config_.node_pool = &node_pool_;
  tree_config_.strategy = config_.strategy;
  tree_config_.max_nodes = std::max(config_.tree_max_nodes, 16);
  tree_config_.max_depth = std::max(config_.tree_max_depth, 1);
  tree_config_.steer_rad_per_s = radians(std::clamp(config_.steer_deg_per_s, 0.0f, 3600.0f));
  terrain_mode_ = config_.locomotion == Locomotion::kTerrain ||
                  (config_.locomotion == Locomotion::kAuto &&
                   (!scene_.terrain.height_field.empty() || !scene_.terrain.steps.empty()));
  terrain_config_.walker.dt_s = 1.0f / static_cast<float>(config_.tick_hz);
  if (terrain_mode_ && (config_.fighters > 0 || (config_.fighters < 0 && !scene_.npcs.empty())))
    std::fprintf(stderr, "foresight-server: no NPC fighters on terrain (they walk the motion graph)\n");
  if (terrain_mode_) config_.fighters = 0;
  SessionSettings sessions;
  sessions.scene_name = scene_.name;
  sessions.library_name = library_.name;
  sessions.library_hash = library_.content_hash;
  sessions.scene_hash = scene_hash_;
  sessions.scene_bytes = static_cast<uint32_t>(scene_file_.size());
  sessions.tick_hz = static_cast<uint16_t>(config_.tick_hz);
  sessions.snapshot_hz = static_cast<uint16_t>(config_.snapshot_hz);
  sessions.max_players = config_.max_players;
  sessions.max_joins_per_tick = config_.max_joins_per_tick;
  sessions.max_challenges_per_tick = config_.max_challenges_per_tick;
  sessions.max_packets_per_s = config_.max_packets_per_s;
  sessions.session_timeout_s = config_.session_timeout_s;
  if (!sessions_.open(config_.bind_address, config_.port, sessions, error)) return false;
  reservations_.configure(scene_.bounds);
  snapshot_archive_ = protocol::SnapshotArchive(protocol::SnapshotArchive::slots_for(config_.tick_hz, config_.snapshot_hz));
  if (!plan_spawn_places(error)) return false;
  workers_ = std::make_unique<LookaheadWorkers>(config_.threads);
  scheduler_ = std::make_unique<LookaheadScheduler>(config_, library_, *workers_);
  for (int w = 0; w < workers_->threads(); ++w) snapshot_builders_.push_back(std::make_unique<SnapshotBuilder>());
  const auto max_players = static_cast<size_t>(std::max(config_.max_players, 0));
  graph_avatars_.reserve(max_players + 256);  // + fighters
  terrain_walkers_.reserve(max_players);
  roster_.reserve(max_players + 256);
  terrain_neighbours_.reserve(max_players);
  snapshot_terrain_.reserve(max_players);
  terrain_before_.reserve(max_players + 257);  // players, fighters, one past
  started_ = Clock::now();
  if (!spawn_fighters(error)) return false;
  if (config_.admin_port >= 0) {
    admin_token_ = config_.admin_token.empty() ? admin_random_token() : config_.admin_token;
    admin_state_ = std::make_shared<AdminState>();
    publish_admin(Clock::now());
    admin_ = std::make_unique<AdminEndpoint>(admin_state_, admin_queue_, admin_token_);
    std::string admin_error;
    if (!admin_->start(config_.admin_bind, config_.admin_port, admin_error)) {
      // An endpoint the operator asked for and did not get is an error at start: an orchestrator
      // probing /healthz on a port another server holds would be told about the wrong server.
      error = admin_error + " (--admin-port -1: no admin endpoint)";
      admin_.reset();
      return false;
    } else {
      std::fprintf(stderr, "foresight-server: admin endpoint http://%s:%d/?token=%s (/metrics, /status, /command)\n",
                   config_.admin_bind.c_str(), admin_->port(), config_.admin_token.empty() ? admin_token_.c_str() : "<yours>");
    }
  }
  if (config_.agones_sdk_port >= 0) {
    AgonesConfig ac;
    ac.port = config_.agones_sdk_port > 0 ? config_.agones_sdk_port : agones_port_from_environment();
    ac.health_interval_s = config_.agones_health_s;
    agones_ = std::make_unique<AgonesSdk>(ac, last_tick_ns_);
    agones_->start();
    std::fprintf(stderr, "foresight-server: Agones SDK sidecar at 127.0.0.1:%d (Ready after the first tick)\n", ac.port);
  }
  std::fprintf(stderr,
               "foresight-server: scene %s, library %s (%d segments, hash %016llx), UDP %s:%u, "
               "%d Hz ticks, %d Hz snapshots, %d look-ahead thread(s), strategy %d, %s locomotion\n",
               scene_.name.c_str(), library_.name.c_str(), library_.graph.num_segments(),
               static_cast<unsigned long long>(library_.content_hash), config_.bind_address.c_str(),
               port(), config_.tick_hz, config_.snapshot_hz, config_.threads,
               static_cast<int>(config_.strategy), terrain_mode_ ? "terrain" : "motion-graph");
  return true;
}

GraphAvatar* Server::graph_avatar(uint32_t id) {
  const RosterEntry* e = roster_.find(id);
  return e != nullptr && e->kind == AvatarKind::kGraph ? graph_avatars_.get(e->avatar) : nullptr;
}

const GraphAvatar* Server::graph_avatar(uint32_t id) const {
  const RosterEntry* e = roster_.find(id);
  return e != nullptr && e->kind == AvatarKind::kGraph ? graph_avatars_.get(e->avatar) : nullptr;
}

const GraphAvatar* Server::player_avatar(uint32_t id) const {
  const GraphAvatar* g = graph_avatar(id);
  return g != nullptr && !g->npc ? g : nullptr;
}

Fighter* Server::fighter(uint32_t id) {
  const GraphAvatar* g = graph_avatar(id);
  return g != nullptr ? fighters_.get(g->fighter) : nullptr;
}

const Fighter* Server::fighter(uint32_t id) const {
  const GraphAvatar* g = graph_avatar(id);
  return g != nullptr ? fighters_.get(g->fighter) : nullptr;
}

const LookaheadAvatar* Server::avatar(uint32_t avatar_id) const {
  const GraphAvatar* g = graph_avatar(avatar_id);
  return g != nullptr ? g->avatar.get() : nullptr;
}

const terrain::TerrainAvatar* Server::terrain_avatar(uint32_t avatar_id) const {
  const RosterEntry* e = roster_.find(avatar_id);
  const TerrainWalker* w = e != nullptr && e->kind == AvatarKind::kTerrain ? terrain_walkers_.get(e->avatar) : nullptr;
  return w != nullptr ? w->avatar.get() : nullptr;
}

std::vector<uint32_t> Server::avatar_ids() const {
  std::vector<uint32_t> ids;
  for (const RosterEntry& e : roster_.entries()) ids.push_back(e.id);
  return ids;
}

void Server::run() {
  enter_realtime();
  const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / config_.tick_hz));
  Clock::time_point next = Clock::now();
  while (!stop_requested_.load()) {
    run_tick(Clock::now());
    next += period;
    const Clock::time_point now = Clock::now();
    if (next < now - period) next = now;  // far behind (debugger, suspend): do not spiral
    std::this_thread::sleep_until(next);
  }
  close_sessions();
}

void Server::enter_realtime() {
  const int priority = config_.realtime_priority;
  if (priority <= 0) return;
  std::string error;
  if (make_realtime(pthread_self(), priority, error) && workers_->make_realtime(priority, error)) {
    realtime_.store(true);
    std::fprintf(stderr, "foresight-server: the tick thread and %d look-ahead worker(s) run in the real-time FIFO class at priority %d\n",
                 workers_->threads() - 1, priority);
  } else {
    std::fprintf(stderr, "foresight-server: %s; ticking at normal priority\n", error.c_str());
  }
}

void Server::close_sessions() {
  sessions_.close_all(*this);
  if (agones_) agones_->shutdown();  // after the players were told
}

// ---------------------------------------------------------------------------------------------
// The tick

void Server::run_tick(Clock::time_point now) {
  // `now` is the protocol's clock (tests pass their own); the work is measured on the real one.
  StageTimer timer;
  static thread_local const ThreadSchedClock sched_clock;  // the thread running the ticks
  const ThreadSchedTimes sched_start = sched_clock.read();
  last_tick_ns_.store(std::chrono::duration_cast<std::chrono::nanoseconds>(timer.start().time_since_epoch()).count(),
                      std::memory_order_relaxed);
  ++tick_;
  TickRecord record;
  // 1 receive: datagrams, then queued joins, then sessions gone silent.
  sessions_.start_tick();
  sessions_.receive(now, *this);
  sessions_.admit_joins(now, *this);
  sessions_.expire(now, *this);
  // 2 commands from the supervisor and the admin endpoint.
  run_admin_commands();
  // 3 think: fighters choose their command as players' keys arrived in 1.
  think_fighters();
  record.receive_ms = timer.lap_ms();
  // 4 the trees take the new commands, then 5 decide and play.
  scheduler_->take_inputs(graph_avatars_.items());
  advance(record);
  record.advance_ms = timer.lap_ms();
  // 6 send: the players see this tick's motion without waiting for the look-ahead.
  send_snapshots(now);
  check_contacts();
  record.send_ms = timer.lap_ms();
  // 7 look ahead until the tick's deadline, for the decisions of the ticks to come: last, so the
  // growth, and nothing else, gives way when the stages before it run slow.
  scheduler_->grow(graph_avatars_.items(), tick_, timer.start(), record);
  timer.lap_ms();  // the scheduler times its own part (record.lookahead_ms)
  // 8 finish.
  const ThreadSchedTimes sched_end = sched_clock.read();
  record.on_cpu_ms = static_cast<float>(static_cast<double>(sched_end.on_cpu_ns - sched_start.on_cpu_ns) * 1e-6);
  record.waiting_ms = static_cast<float>(static_cast<double>(sched_end.waiting_ns - sched_start.waiting_ns) * 1e-6);
  finish_tick(record, timer);
}

void Server::run_admin_commands() {
  admin_queue_->take(admin_requests_);
  for (const AdminRequest& r : admin_requests_) {
    const AdminReply reply = admin_command(r.line);
    if (r.reply) {
      r.reply(reply);
    } else {
      std::printf("%s%s\n", reply.status == 200 ? "" : "error: ", reply.text.c_str());
      std::fflush(stdout);
    }
  }
}

void Server::finish_tick(TickRecord& record, const StageTimer& timer) {
  record.players = num_players();
  record.tick_ms = timer.total_ms();
  const bool overrun = record.tick_ms > 1000.0f / static_cast<float>(config_.tick_hz);
  stats_.record(record, overrun);
  if (overrun && tick_ >= next_overrun_log_tick_) {  // at most one line a second
    next_overrun_log_tick_ = tick_ + static_cast<uint32_t>(config_.tick_hz);
    std::fprintf(stderr,
                 "foresight-server: tick %u overran: %.1f ms (receive %.1f, advance %.1f, send %.1f, look-ahead %.1f "
                 "of %.1f; the tick thread on a CPU %.1f, waiting for one %.1f), %d players, %llu overruns so far\n",
                 tick_, record.tick_ms, record.receive_ms, record.advance_ms, record.send_ms, record.lookahead_ms,
                 record.budget_ms, record.on_cpu_ms, record.waiting_ms, record.players,
                 static_cast<unsigned long long>(stats_.overruns()));
  }
  if (admin_) publish_admin(Clock::now());
  const auto status_ticks = static_cast<uint32_t>(config_.status_every_s * config_.tick_hz);
  if (status_ticks > 0 && tick_ % status_ticks == 0) log_status();
}

void Server::publish_admin(Clock::time_point now) {
  const ServerCounters& c = counters_;
  // Memory once a second (a /proc read and a walk over the players), outside the lock.
  const bool memory_due = tick_ % static_cast<uint32_t>(config_.tick_hz) == 0;
  MemoryFigures memory;
  if (memory_due) memory = memory_figures();
  std::lock_guard<std::mutex> lock(admin_state_->mutex);
  AdminMetrics& m = admin_state_->metrics;
  m.tick = tick_;
  m.uptime_s = std::chrono::duration<double>(now - started_).count();
  m.tick_hz = config_.tick_hz;
  m.snapshot_hz = config_.snapshot_hz;
  m.players = num_players();
  m.max_players = config_.max_players;
  m.fighters = num_fighters_;
  m.joins_waiting = static_cast<int>(sessions_.joins_waiting());
  if (m.scene.empty()) {  // once: no allocation per tick
    m.scene = scene_.name;
    m.locomotion = terrain_mode_ ? "terrain" : "graph";
  }
  m.strategy = strategy_name(config_.strategy);
  m.budget_limit_ms = config_.lookahead_budget_ms;
  m.margin_ms = config_.tick_safety_margin_ms;
  m.realtime = realtime_.load();
  m.tick_buckets = stats_.buckets();
  m.ticks = stats_.ticks();
  m.overruns = stats_.overruns();
  m.tick_ms_sum = stats_.tick_ms_sum();
  m.tick_ms_p50 = stats_.tick_ms_percentile(50);
  m.tick_ms_p99 = stats_.tick_ms_percentile(99);
  m.tick_ms_max = stats_.tick_ms_max();
  m.last = stats_.last();
  m.mean = stats_.mean();
  m.expansions_total = stats_.expansions_total();
  m.packets_in = c.packets_in, m.bytes_in = c.bytes_in, m.packets_out = c.packets_out, m.bytes_out = c.bytes_out;
  m.send_failures = c.send_failures;
  m.sessions_opened = c.sessions_opened, m.sessions_timed_out = c.sessions_timed_out;
  m.sessions_closed = c.sessions_closed, m.refused = c.refused, m.spawn_refusals = c.spawn_refusals;
  m.challenges_sent = c.challenges_sent, m.challenges_capped = c.challenges_capped, m.joins_deferred = c.joins_deferred;
  m.avatar_contacts = c.avatar_contacts, m.fallbacks = c.fallbacks, m.steered_frames = c.steered_frames;
  m.recoveries = c.recoveries;
  m.fighter_strikes = c.fighter_strikes, m.fighter_hits = c.fighter_hits;
  m.terrain_steps = c.terrain_steps, m.terrain_pivots = c.terrain_pivots, m.terrain_refusals = c.terrain_refusals;
  m.avatars_sent = c.avatars_sent, m.avatars_referenced = c.avatars_referenced;
  if (memory_due) m.memory = memory;
  std::copy(c.drops.by_reason.begin(), c.drops.by_reason.end(), m.drops.begin());
  m.published = std::chrono::steady_clock::now();
}

MemoryFigures Server::memory_figures() const {
  MemoryFigures f;
  f.resident_bytes = resident_memory_bytes();
  f.heap_trim_ms = heap_trimmer_.last_ms();
  for (const GraphAvatar& g : graph_avatars_.items()) f.tree_node_bytes += g.avatar->tree().node_bytes();
  f.tree_node_bytes += node_pool_.bytes_spare();
  for (const Session& s : sessions_.sessions()) f.snapshot_history_bytes += s.sent_views.bytes();
  f.snapshot_history_bytes += snapshot_archive_.bytes();
  return f;
}

void Server::log_status() const {
  const TickRecord mean = stats_.mean();
  std::fprintf(stderr,
               "foresight-server: tick %u, %d players; tick ms p50 %.2f p99 %.2f, %llu overruns; mean ms: "
               "receive %.2f, look-ahead %.1f of %.1f, advance %.2f, send %.2f; %lld expansions/tick, tree "
               "size mean %.0f min %d; %llu packets in, %llu dropped; joins %llu (%llu deferred, %llu refused); "
               "%llu avatar contacts; %d fighters, %llu strikes, %llu hits; terrain %.2f ms/tick, %llu steps, "
               "%llu turns on the spot, %llu refusals; %.0f %% of avatars delta-coded\n",
               tick_, num_players(), stats_.tick_ms_percentile(50), stats_.tick_ms_percentile(99),
               static_cast<unsigned long long>(stats_.overruns()), mean.receive_ms, mean.lookahead_ms,
               mean.budget_ms, mean.advance_ms, mean.send_ms,
               static_cast<long long>(mean.expansions), mean.tree_size_mean, mean.tree_size_min,
               static_cast<unsigned long long>(counters_.packets_in),
               static_cast<unsigned long long>(counters_.drops.total()),
               static_cast<unsigned long long>(counters_.sessions_opened),
               static_cast<unsigned long long>(counters_.joins_deferred),
               static_cast<unsigned long long>(counters_.refused),
               static_cast<unsigned long long>(counters_.avatar_contacts), num_fighters_,
               static_cast<unsigned long long>(counters_.fighter_strikes),
               static_cast<unsigned long long>(counters_.fighter_hits), mean.terrain_ms,
               static_cast<unsigned long long>(counters_.terrain_steps),
               static_cast<unsigned long long>(counters_.terrain_pivots),
               static_cast<unsigned long long>(counters_.terrain_refusals),
               counters_.avatars_sent ? 100.0 * static_cast<double>(counters_.avatars_referenced) /
                                            static_cast<double>(counters_.avatars_sent)
                                      : 0.0);
}

// ---------------------------------------------------------------------------------------------
// Sessions: what joining, a session's messages and leaving mean in the game

bool Server::on_join(Session& s, Clock::time_point, wire::RefuseReason& reason, std::string& why) {
  Placement spawn;
  if (!find_spawn(spawn)) {
    ++counters_.spawn_refusals;
    reason = wire::RefuseReason::NoSpawnPlace;
    why = "no free spawn place: every place near the spawns is taken by other avatars; try again later";
    return false;
  }
  const uint32_t id = next_avatar_;
  if (terrain_mode_) {
    auto walker = std::make_unique<terrain::TerrainAvatar>();
    if (!terrain::terrain_avatar_init(*walker, terrain_config_, scene_, spawn.pos_m, spawn.heading_rad)) {
      ++counters_.spawn_refusals;
      reason = wire::RefuseReason::NoSpawnPlace;
      why = "no ground at the free spawn place: try again later";
      return false;
    }
    roster_.add({id, AvatarKind::kTerrain, terrain_walkers_.add({id, std::move(walker), {}})});
  } else {
    GraphAvatar g;
    g.id = id;
    g.avatar = std::make_unique<LookaheadAvatar>(library_, world_, tree_config_, spawn_segment_, spawn);
    roster_.add({id, AvatarKind::kGraph, graph_avatars_.add(std::move(g))});
    // Reserve the spawn at once, so a second player joining this tick keeps clear of it.
    reservations_.add(static_cast<int>(id), library_, spawn_segment_, 0, spawn);
  }
  ++next_avatar_;
  s.avatar_id = id;
  return true;
}

void Server::on_leave(const Session& s) {
  const RosterEntry* e = roster_.find(s.avatar_id);
  if (e == nullptr) return;
  // A leaving avatar's tree gives its chunks back to the node pool: cheap, so a crowd leaving at
  // once does not stall the tick (freeing whole per-avatar pools did, ~0.2 ms each).
  if (e->kind == AvatarKind::kGraph) {
    graph_avatars_.remove(e->avatar);
  } else {
    terrain_walkers_.remove(e->avatar);
  }
  roster_.remove(s.avatar_id);
}

void Server::on_message(Session& s, const wire::Packet& message) {
  using wire::Message;
  switch (message.message_type()) {
    case Message::Input: on_input(s, *message.message_as_Input()); break;
    case Message::StatsRequest: send_stats(s); break;
    case Message::TreeRequest: send_tree(s); break;
    case Message::SceneRequest: send_scene_part(s, message.message_as_SceneRequest()->offset()); break;
    default: break;
  }
}

void Server::on_input(Session& s, const wire::Input& m) {
  // The client holds that snapshot whole: later ones may code its avatars against it (merged
  // when the client is next served, on a worker).
  s.sent_views.queue_acknowledgement(snapshot_archive_, m.ack_snapshot());
  s.echo_client_time_ms = m.client_time_ms();
  const auto* commands = m.commands();
  if (commands == nullptr || commands->size() == 0) return;
  if (commands->size() > static_cast<flatbuffers::uoffset_t>(protocol::kInputRedundancy)) {
    counters_.drops.add(protocol::DropReason::kInvalidInput);
    return;
  }
  // Commands are held directions: the newest one not yet applied is what the player holds now.
  // Older ones in the packet were either applied already or superseded.
  const wire::InputCommand* newest = commands->Get(commands->size() - 1);
  if (s.any_input && static_cast<int32_t>(newest->sequence() - s.last_input_seq) <= 0) return;
  const ControlInput in = protocol::control_input_from_command(*newest);
  s.last_input_seq = newest->sequence();
  s.any_input = true;
  const RosterEntry* e = roster_.find(s.avatar_id);
  if (e == nullptr) return;
  if (e->kind == AvatarKind::kTerrain) {
    terrain_walkers_.get(e->avatar)->input = in;
    return;
  }
  GraphAvatar& g = *graph_avatars_.get(e->avatar);
  if (in.camera_dir != g.input.camera_dir || in.camera_yaw_rad != g.input.camera_yaw_rad || in.crouch != g.input.crouch) {
    g.input = in;
    g.input_changed = true;
  }
}

// ---------------------------------------------------------------------------------------------
// Sending

void Server::send_scene_part(Session& s, uint32_t offset) {
  if (offset >= scene_file_.size()) {
    counters_.drops.add(protocol::DropReason::kUnexpected);
    return;
  }
  const uint32_t n = std::min<uint32_t>(protocol::kScenePartBytes, static_cast<uint32_t>(scene_file_.size()) - offset);
  auto& writer = sessions_.writer();
  auto& fbb = writer.begin();
  const auto data = fbb.CreateVector(reinterpret_cast<const uint8_t*>(scene_file_.data()) + offset, n);
  sessions_.send_sealed(s, writer.finish(wire::CreateScenePart(fbb, scene_hash_, static_cast<uint32_t>(scene_file_.size()),
                                                      offset, data)));
  ++counters_.scene_parts_sent;
}

void Server::send_stats(Session& s) {
  const TickRecord mean = stats_.mean();
  auto& writer = sessions_.writer();
  auto& fbb = writer.begin();
  wire::ServerStatsBuilder b(fbb);
  b.add_tick(tick_);
  b.add_players(static_cast<uint32_t>(num_players()));
  b.add_tick_hz(static_cast<uint16_t>(config_.tick_hz));
  b.add_tick_ms_p50(stats_.tick_ms_percentile(50));
  b.add_tick_ms_p99(stats_.tick_ms_percentile(99));
  b.add_tick_ms_max(stats_.tick_ms_max());
  b.add_overruns(stats_.overruns());
  b.add_budget_ms_mean(mean.budget_ms);
  b.add_lookahead_ms_mean(mean.lookahead_ms);
  b.add_expansions_per_tick_mean(static_cast<float>(mean.expansions));
  b.add_tree_size_mean(mean.tree_size_mean);
  b.add_tree_size_min(static_cast<uint32_t>(std::max(0, mean.tree_size_min)));
  b.add_packets_in(counters_.packets_in);
  b.add_packets_dropped(counters_.drops.total());
  b.add_avatar_contacts(counters_.avatar_contacts);
  sessions_.send_sealed(s, writer.finish(b.Finish()));
}

void Server::send_tree(Session& s) {
  // Only ever the requester's own tree: the session named in the request is the player's.
  const GraphAvatar* g = graph_avatar(s.avatar_id);
  if (g == nullptr) return;  // a terrain avatar has none
  sessions_.send_sealed(s, tree_summary_.write(sessions_.writer(), g->avatar->tree(), tick_, s.avatar_id));
}

// Each client gets snapshot_hz snapshots a second on its own phase (its avatar id), so every tick
// serves about snapshot_hz / tick_hz of the clients, rather than all of them on two ticks of three
// and none on the third: the send phase then costs the same every tick and the look-ahead budget,
// sized on the ticks before, fits (docs/SERVER.md "The tick"). A client's snapshots come as before
// (20 Hz: 33, 33 and 67 ms apart). The archive numbers the snapshots gathered; each client
// numbers the ones it gets one by one (SnapshotReceiver::snapshot, this function's count).
uint64_t Server::snapshots_by(uint32_t tick, uint32_t avatar_id) const {
  const auto hz = static_cast<uint64_t>(std::max(config_.tick_hz, 1));
  const uint64_t phase = avatar_id % hz;
  return (tick + phase) * static_cast<uint64_t>(std::clamp(config_.snapshot_hz, 1, config_.tick_hz)) / hz;
}

void Server::send_snapshots(Clock::time_point now) {
  snapshot_receivers_.clear();
  for (Session& s : sessions_.sessions()) {
    const uint64_t served = snapshots_by(tick_, s.avatar_id);
    if (served == snapshots_by(tick_ - 1, s.avatar_id)) continue;  // not this client's tick
    const int index = roster_.index_of(s.avatar_id);  // every session has its avatar (on_join)
    assert(index >= 0);
    // Far avatars in every far_every-th of the client's own snapshots, staggered by client.
    const bool far_due =
        config_.far_every > 0 && (served + s.avatar_id) % static_cast<uint64_t>(config_.far_every) == 0;
    snapshot_receivers_.push_back({static_cast<uint32_t>(served), static_cast<uint32_t>(index), s.avatar_id,
                                   s.last_input_seq, s.echo_client_time_ms, far_due, &s.endpoint, &s.sealer,
                                   &s.sent_views});
  }
  if (snapshot_receivers_.empty()) return;
  ++snapshots_gathered_;
  snapshot_states_.clear();
  snapshot_terrain_.clear();
  terrain_before_.clear();
  snapshot_positions_.clear();
  // In id order (the roster's): a client's view (increasing indices into these arrays) is then
  // sorted by id, as the packed avatars want it.
  for (const RosterEntry& e : roster_.entries()) {
    terrain_before_.push_back(static_cast<uint32_t>(snapshot_terrain_.size()));
    if (e.kind == AvatarKind::kTerrain) {
      const TerrainWalker& w = *terrain_walkers_.get(e.avatar);
      snapshot_positions_.push_back(terrain::terrain_avatar_ground(*w.avatar));
      collect_terrain_body(w);
      continue;
    }
    const GraphAvatar& g = *graph_avatars_.get(e.avatar);
    snapshot_positions_.push_back(g.avatar->root().pos_m);
    const PlaybackState& s = g.avatar->playback();
    const bool fallback = g.avatar->tree().node(g.avatar->tree().root()).first_child < 0;
    snapshot_states_.emplace_back(
        g.id, protocol::quantize_mm(s.segment_start.pos_m.x), protocol::quantize_mm(s.segment_start.pos_m.y),
        s.incoming_transition, static_cast<uint16_t>(s.segment), protocol::quantize_angle(s.segment_start.heading_rad),
        static_cast<uint8_t>(std::clamp(s.frame, 0, 255)),
        static_cast<uint8_t>((fallback ? protocol::kAvatarFallback : protocol::kAvatarNone) |
                             (g.npc ? protocol::kAvatarNpc : protocol::kAvatarNone) |
                             (g.striking ? protocol::kAvatarStriking : protocol::kAvatarNone)),
        0);
  }
  terrain_before_.push_back(static_cast<uint32_t>(snapshot_terrain_.size()));
  protocol::SnapshotArchive::Slot& archived = snapshot_archive_.start(snapshots_gathered_, static_cast<uint32_t>(tick_));
  archived.avatars.assign(snapshot_states_.begin(), snapshot_states_.end());
  collect_fighter_poses();
  const bool interest = config_.interest_radius_m > 0;
  if (interest) interest_grid_.build(snapshot_positions_, config_.interest_radius_m);
  SnapshotFrame frame;
  frame.server_tick = static_cast<uint32_t>(tick_);
  frame.server_ms = static_cast<uint32_t>(ms_between(started_, now));
  frame.states = snapshot_states_;
  frame.positions = snapshot_positions_;
  frame.terrain = snapshot_terrain_;
  frame.terrain_before = terrain_before_;
  frame.fighters = fighter_poses_;
  frame.fighter_rotations = fighter_rotations_;
  frame.events = snapshot_events_;
  frame.interest = interest ? &interest_grid_ : nullptr;
  frame.interest_radius_m = config_.interest_radius_m;
  frame.far_radius_m = config_.far_radius_m;
  frame.archived = &archived;
  frame.archive = &snapshot_archive_;
  // Clients in parallel on the look-ahead workers, each worker with its own builder and batch.
  workers_->run(static_cast<int>(snapshot_receivers_.size()), [this, &frame](int item, int worker) {
    snapshot_builders_[static_cast<size_t>(worker)]->serve(frame, snapshot_receivers_[static_cast<size_t>(item)],
                                                           sessions_.socket());
  });
  for (auto& builder : snapshot_builders_) {
    builder->flush(sessions_.socket());
    const SnapshotBuilder::Counts c = builder->take_counts();
    counters_.avatars_sent += c.avatars_sent;
    counters_.avatars_referenced += c.avatars_referenced;
    counters_.packets_out += c.datagrams.sent;
    counters_.bytes_out += c.datagrams.bytes;
    counters_.send_failures += c.datagrams.failed;
  }
}

// ---------------------------------------------------------------------------------------------
// Simulation

std::vector<Placement> Server::free_places_around(std::span<const Placement> around, size_t max_places) const {
  // Rings 0.25 m apart up to 8 m out, points 0.25 m apart along each ring, the rings of all the
  // points interleaved so that every spawn's nearest places come first. At each point the first
  // of four headings (the spawn's first) that fits: a body longer than wide may fit turned.
  constexpr float kStep_m = 0.25f, kMaxRadius_m = 8.0f;
  std::vector<Placement> places;
  const int rings = static_cast<int>(kMaxRadius_m / kStep_m);
  for (int ring = 0; ring <= rings && places.size() < max_places; ++ring) {
    const float r = kStep_m * static_cast<float>(ring);
    const int count = std::max(1, static_cast<int>(std::ceil(kTwoPi * r / kStep_m)));
    for (const Placement& centre : around) {
      for (int k = 0; k < count && places.size() < max_places; ++k) {
        const float a = kTwoPi * static_cast<float>(k) / static_cast<float>(count);
        for (int turn = 0; turn < 4; ++turn) {
          const Placement p{centre.pos_m + r * vec2(std::sin(a), std::cos(a)),
                            wrap_angle(centre.heading_rad + 0.5f * kPi * static_cast<float>(turn))};
          if (!scene_.bounds.contains(p.pos_m)) break;
          const bool free = terrain_mode_ ? terrain_place_free(p)
                                          : segment_feasible(world_, library_.segment_shapes[static_cast<size_t>(spawn_segment_)], p);
          if (free) {
            places.push_back(p);
            break;
          }
        }
      }
    }
  }
  return places;
}

bool Server::place_is_free_now(const Placement& p) const {
  return terrain_mode_ ? terrain_place_free(p) : !reservations_.blocks(-1, library_, spawn_segment_, p);
}

bool Server::find_spawn(Placement& out) {
  for (const bool recent_too : {false, true}) {
    for (size_t i = 0; i < spawn_places_.size(); ++i) {
      uint32_t& taken_at = spawn_place_taken_at_[i];
      const bool recent = taken_at != 0 && tick_ - taken_at < kSpawnRecheckTicks;
      // The first pass looks at the places not found taken lately; the second at those found
      // taken in the ticks before this one (not again at those this tick's joins just checked).
      if (recent_too ? (!recent || taken_at == tick_) : recent) continue;
      const bool free = place_is_free_now(spawn_places_[i]);
      taken_at = tick_;  // given out now, or taken
      if (free) {
        out = spawn_places_[i];
        return true;
      }
    }
  }
  return false;
}

bool Server::find_free_place(std::span<const Placement> around, Placement& out) const {
  for (const Placement& p : free_places_around(around, 256)) {
    if (place_is_free_now(p)) {
      out = p;
      return true;
    }
  }
  return false;
}

bool Server::plan_spawn_places(std::string& error) {
  std::vector<Placement> around;
  for (const SpawnPoint& sp : scene_.spawns) {
    const Placement at{sp.pos_m, sp.heading_rad};
    around.push_back(at);
    if (terrain_mode_) continue;
    if (const std::string why = body_fit_problem(library_, scene_, world_, spawn_segment_, at); !why.empty())
      std::fprintf(stderr, "foresight-server: spawn '%s' at (%.2f, %.2f): %s; players start at the nearest free place\n",
                   sp.name.c_str(), static_cast<double>(sp.pos_m.x), static_cast<double>(sp.pos_m.y), why.c_str());
  }
  spawn_places_ = free_places_around(around, kMaxSpawnPlaces);
  spawn_place_taken_at_.assign(spawn_places_.size(), 0);
  if (spawn_places_.empty()) {
    error = "scene '" + scene_.name + "': no place within 8 m of any spawn fits the avatar's standing body";
    return false;
  }
  return true;
}

void Server::advance(TickRecord& record) {
  // Reservations: every avatar's committed motion as it stands now.
  reservations_.clear();
  for (const GraphAvatar& g : graph_avatars_.items()) {
    const PlaybackState& s = g.avatar->playback();
    reservations_.add(static_cast<int>(g.id), library_, s.segment, s.frame, s.segment_start);
  }
  const double fps = library_.clips.empty() ? 30.0 : library_.clips.front().fps;
  const int64_t due = frames_due(tick_, fps, config_.tick_hz) - frames_due(tick_ - 1, fps, config_.tick_hz);
  for (GraphAvatar& g : graph_avatars_.items()) {
    for (int64_t f = 0; f < due; ++f) {
      const ReservationVeto veto(reservations_, library_, static_cast<int>(g.id), g.avatar->fallback_segment());
      const AvatarStepResult r = g.avatar->step(&veto);
      if (r.fallback) ++counters_.fallbacks;
      if (r.steered) ++counters_.steered_frames;
      if (r.recovery) ++counters_.recoveries;
      if (r.segment_changed || r.steered) {  // committed: reserve it now for the players deciding after
        const PlaybackState& s = g.avatar->playback();
        reservations_.add(static_cast<int>(g.id), library_, s.segment, s.frame, s.segment_start);
      }
    }
  }
  animate_fighters(due);
  advance_terrain(record);
}

void Server::check_contacts() {
  // Independent of the reservations and the terrain veto: do two avatars' bodies (this frame's
  // volumes; a terrain body's pelvis circle) overlap?
  contact_bodies_.clear();
  for (const TerrainWalker& w : terrain_walkers_.items())
    contact_bodies_.push_back({terrain::terrain_avatar_ground(*w.avatar), terrain::kTerrainBodyRadius_m});
  for (const GraphAvatar& g : graph_avatars_.items()) {
    const PlaybackState& s = g.avatar->playback();
    contact_bodies_.push_back(place(library_.volumes(s.segment)[static_cast<size_t>(s.frame)], s.segment_start));
  }
  if (any_footprints_overlap(contact_bodies_)) ++counters_.avatar_contacts;
}

}  // namespace foresight::server

#include "server.hpp"

#include "io/text_file.hpp"
#include "library/body_fit.hpp"

#include "player.hpp"

#include "protocol/player_name.hpp"
#include "protocol/input_packet.hpp"
#include "protocol/quantize.hpp"
#include "transport/scene_transfer.hpp"
#include "world/data_paths.hpp"
#include "world/scene_load.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <thread>

namespace foresight::server {

namespace {

double ms_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

bool same_endpoint(const protocol::Endpoint& a, const protocol::Endpoint& b) {
  return a.address() == b.address() && a.port() == b.port();
}

// A hash key for the player table (IPv4: exact; IPv6: hashed, confirmed by same_endpoint).
uint64_t endpoint_key(const protocol::Endpoint& e) {
  std::array<uint8_t, 16> storage;
  const auto bytes = protocol::endpoint_address_bytes(e, storage);
  uint64_t h = 1469598103934665603ull;  // FNV-1a
  for (uint8_t b : bytes) h = (h ^ b) * 1099511628211ull;
  return (h << 16) ^ e.port();
}

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
  if (!socket_.open(config_.bind_address, config_.port, error)) return false;
  receive_buffer_.resize(protocol::kMaxDatagramBytes + 1);
  reservations_.configure(scene_.bounds);
  if (!plan_spawn_places(error)) return false;
  workers_ = std::make_unique<LookaheadWorkers>(config_.threads);
  for (int w = 0; w < workers_->threads(); ++w) snapshot_builders_.push_back(std::make_unique<SnapshotBuilder>());
  grow_deadline_.resize(static_cast<size_t>(config_.threads));
  players_.reserve(static_cast<size_t>(config_.max_players));
  tree_players_.reserve(players_.capacity() + 256);  // + fighters
  terrain_neighbours_.reserve(players_.capacity());
  snapshot_terrain_.reserve(players_.capacity());
  terrain_before_.reserve(players_.capacity() + 257);  // players, fighters, one past
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

int Server::num_players() const { return static_cast<int>(players_.size()) - num_fighters_; }

const LookaheadAvatar* Server::avatar(uint32_t avatar_id) const {
  for (const auto& p : players_)
    if (p->avatar_id == avatar_id) return p->avatar.get();
  return nullptr;
}

const terrain::TerrainAvatar* Server::terrain_avatar(uint32_t avatar_id) const {
  for (const auto& p : players_)
    if (p->avatar_id == avatar_id) return p->terrain.get();
  return nullptr;
}

std::vector<uint32_t> Server::avatar_ids() const {
  std::vector<uint32_t> ids;
  for (const auto& p : players_) ids.push_back(p->avatar_id);
  return ids;
}

void Server::run() {
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

void Server::close_sessions() {
  for (size_t i = players_.size(); i-- > 0;) {
    if (players_[i]->is_fighter()) continue;
    for (int copy = 0; copy < 2; ++copy) {
      auto& fbb = writer_.begin();
      const auto text = fbb.CreateString("the server is shutting down");
      send_sealed(*players_[i], writer_.finish(wire::CreateRefuse(fbb, wire::RefuseReason::ShuttingDown, text,
                                                                  library_.content_hash)));
    }
    ++counters_.sessions_closed;
    remove_player(i);
  }
  join_queue_.clear();
  if (agones_) agones_->shutdown();  // after the players were told
}

void Server::run_tick(Clock::time_point now) {
  // `now` is the protocol's clock (tests pass their own); the work is measured on the real one.
  const Clock::time_point tick_start = Clock::now();
  last_tick_ns_.store(std::chrono::duration_cast<std::chrono::nanoseconds>(
                          std::chrono::steady_clock::now().time_since_epoch())
                          .count(),
                      std::memory_order_relaxed);
  ++tick_;
  challenges_this_tick_ = 0;
  TickRecord record;
  receive(now);
  admit_joins(now);
  expire(now);
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
  think_fighters(now);
  const Clock::time_point received = Clock::now();
  record.receive_ms = static_cast<float>(ms_between(tick_start, received));
  // Look ahead, then decide: the avatar's order of LookaheadAvatar (set_input, grow, step).
  grow_trees(tick_start, received, record);
  const Clock::time_point grown = Clock::now();
  advance(record);
  const Clock::time_point advanced = Clock::now();
  record.advance_ms = static_cast<float>(ms_between(grown, advanced));
  send_snapshots(now);
  check_contacts();
  record.send_ms = static_cast<float>(ms_between(advanced, Clock::now()));
  tail_ms_estimate_ = 0.9 * tail_ms_estimate_ + 0.1 * (record.advance_ms + record.send_ms);
  record.players = num_players();
  for (int i = 0; i < 4 && !retired_.empty(); ++i) retired_.pop_back();
  record.tick_ms = static_cast<float>(ms_between(tick_start, Clock::now()));
  const bool overrun = record.tick_ms > 1000.0f / static_cast<float>(config_.tick_hz);
  stats_.record(record, overrun);
  if (overrun && tick_ >= next_overrun_log_tick_) {  // at most one line a second
    next_overrun_log_tick_ = tick_ + static_cast<uint32_t>(config_.tick_hz);
    std::fprintf(stderr,
                 "foresight-server: tick %u overran: %.1f ms (receive %.1f, look-ahead %.1f of %.1f, advance %.1f, "
                 "send %.1f), %d players, %llu overruns so far\n",
                 tick_, record.tick_ms, record.receive_ms, record.lookahead_ms, record.budget_ms, record.advance_ms,
                 record.send_ms, record.players, static_cast<unsigned long long>(stats_.overruns()));
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
  m.joins_waiting = static_cast<int>(join_queue_.size());
  if (m.scene.empty()) {  // once: no allocation per tick
    m.scene = scene_.name;
    m.locomotion = terrain_mode_ ? "terrain" : "graph";
  }
  m.strategy = strategy_name(config_.strategy);
  m.budget_limit_ms = config_.lookahead_budget_ms;
  m.margin_ms = config_.tick_safety_margin_ms;
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
  for (const auto& p : players_) {
    if (p->avatar) f.tree_node_bytes += p->avatar->tree().node_bytes();
    f.snapshot_history_bytes += p->sent_views.bytes();
  }
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
// Receiving

void Server::receive(Clock::time_point now) {
  protocol::Endpoint from;
  // Bounded: a flood cannot keep the tick in here (what is left waits for the next tick).
  for (int budget = 20000; budget > 0; --budget) {
    const ptrdiff_t n = socket_.receive(receive_buffer_, from);
    if (n < 0) break;
    ++counters_.packets_in;
    counters_.bytes_in += static_cast<uint64_t>(n);
    protocol::DropReason reason;
    const wire::Packet* packet =
        protocol::packet_read({receive_buffer_.data(), static_cast<size_t>(n)}, reason);
    if (packet == nullptr) {
      counters_.drops.add(reason);
      continue;
    }
    handle(from, *packet, static_cast<size_t>(n), now);
  }
}

Server::Player* Server::find_player(const protocol::Endpoint& from) {
  const auto it = by_endpoint_.find(endpoint_key(from));
  return it != by_endpoint_.end() && same_endpoint(it->second->endpoint, from) ? it->second : nullptr;
}

void Server::handle(const protocol::Endpoint& from, const wire::Packet& packet, size_t bytes,
                    Clock::time_point now) {
  using wire::Message;
  switch (packet.message_type()) {
    case Message::ConnectRequest:
      on_connect_request(from, *packet.message_as_ConnectRequest(), bytes, now);
      return;
    case Message::ConnectResponse:
      on_connect_response(from, *packet.message_as_ConnectResponse(), now);
      return;
    case Message::Sealed: break;
    case Message::Input:
    case Message::Heartbeat:
    case Message::Disconnect:
    case Message::StatsRequest:
    case Message::TreeRequest:  // only inside a Sealed message: anyone could have sent this
    case Message::SceneRequest:
      counters_.drops.add(protocol::DropReason::kUnauthenticated);
      return;
    default: counters_.drops.add(protocol::DropReason::kUnexpected); return;
  }
  // A session's message: the sender must be a player.
  Player* p = find_player(from);
  if (p == nullptr) {
    counters_.drops.add(protocol::DropReason::kUnexpected);
    return;
  }
  protocol::DropReason reason = protocol::DropReason::kNone;
  const wire::Packet* inner = p->opener.open(*packet.message_as_Sealed(), reason);
  if (inner == nullptr) {
    counters_.drops.add(reason);  // forged, corrupted, another session's, or replayed
    return;
  }
  // Token bucket: max_packets_per_s sustained, one second's worth of burst. Charged only for
  // what the player really sent: charged before opening, datagrams forged with the player's
  // address spent its allowance and its own inputs were dropped (issue 19). Opening is a few
  // hundred nanoseconds, and receive() takes a bounded number of datagrams a tick.
  const double rate = config_.max_packets_per_s;
  p->tokens = std::min(rate, p->tokens + rate * std::chrono::duration<double>(now - p->tokens_at).count());
  p->tokens_at = now;
  if (p->tokens < 1.0) {
    counters_.drops.add(protocol::DropReason::kRateLimited);
    return;
  }
  p->tokens -= 1.0;
  handle_session(*p, *inner, now);
}

void Server::handle_session(Player& p, const wire::Packet& packet, Clock::time_point now) {
  using wire::Message;
  uint32_t session = 0;
  if (auto* m = packet.message_as_Input()) session = m->session();
  if (auto* m = packet.message_as_Heartbeat()) session = m->session();
  if (auto* m = packet.message_as_Disconnect()) session = m->session();
  if (auto* m = packet.message_as_StatsRequest()) session = m->session();
  if (auto* m = packet.message_as_TreeRequest()) session = m->session();
  if (auto* m = packet.message_as_SceneRequest()) session = m->session();
  if (p.session != session) {  // sealed by this session's key, yet naming another
    counters_.drops.add(protocol::DropReason::kUnexpected);
    return;
  }
  p.last_heard = now;
  switch (packet.message_type()) {
    case Message::Input: on_input(p, *packet.message_as_Input()); break;
    case Message::Heartbeat: p.echo_client_time_ms = packet.message_as_Heartbeat()->client_time_ms(); break;
    case Message::StatsRequest: send_stats(p); break;
    case Message::TreeRequest: send_tree(p); break;
    case Message::SceneRequest: send_scene_part(p, packet.message_as_SceneRequest()->offset()); break;
    case Message::Disconnect:
      ++counters_.sessions_closed;
      for (size_t i = 0; i < players_.size(); ++i)
        if (players_[i].get() == &p) {
          remove_player(i);
          break;
        }
      break;
    default: break;
  }
}

void Server::on_connect_request(const protocol::Endpoint& from, const wire::ConnectRequest& m,
                                size_t bytes, Clock::time_point now) {
  if (bytes < protocol::kMinConnectRequestBytes) {
    counters_.drops.add(protocol::DropReason::kTooSmall);  // unpadded: could amplify
    return;
  }
  // Every answer to an address not yet proven (a challenge or a refusal) shares one per-tick
  // budget: refusals of a wrong version were sent before it, 1,000 requests got 1,000 answers,
  // an uncapped reflector (issue 19).
  if (challenges_this_tick_ >= config_.max_challenges_per_tick) {
    ++counters_.challenges_capped;
    return;
  }
  ++challenges_this_tick_;
  if (m.protocol() != protocol::kProtocolVersion) {
    send_refuse(from, wire::RefuseReason::ProtocolVersion,
                "protocol version " + std::to_string(m.protocol()) + " is not the server's " +
                    std::to_string(protocol::kProtocolVersion) + ": update the client");
    return;
  }
  std::array<uint8_t, 16> storage;
  const auto seconds = static_cast<uint64_t>(std::chrono::duration_cast<std::chrono::seconds>(now.time_since_epoch()).count());
  const protocol::Cookie cookie = cookies_.make(protocol::endpoint_address_bytes(from, storage), from.port(), seconds);
  auto& fbb = writer_.begin();
  const auto c = fbb.CreateVector(cookie.data(), cookie.size());
  send(writer_.finish(wire::CreateChallenge(fbb, c)), from);
  ++counters_.challenges_sent;
}

void Server::on_connect_response(const protocol::Endpoint& from, const wire::ConnectResponse& m,
                                 Clock::time_point now) {
  if (Player* existing = find_player(from)) {  // our Accept was lost: say it again
    send_accept(*existing);
    return;
  }
  std::array<uint8_t, 16> storage;
  const auto seconds = static_cast<uint64_t>(std::chrono::duration_cast<std::chrono::seconds>(now.time_since_epoch()).count());
  const auto* cookie = m.cookie();
  if (cookie == nullptr ||
      !cookies_.check({cookie->data(), cookie->size()}, protocol::endpoint_address_bytes(from, storage),
                      from.port(), seconds)) {
    // The sender's address is unproven: a refusal to it shares the challenges' per-tick budget, so
    // forged responses cannot make the server a reflector either.
    if (challenges_this_tick_ >= config_.max_challenges_per_tick) {
      ++counters_.challenges_capped;
      return;
    }
    ++challenges_this_tick_;
    send_refuse(from, wire::RefuseReason::BadCookie, "connection cookie wrong or expired: connect again");
    return;
  }
  if (m.protocol() != protocol::kProtocolVersion) {
    send_refuse(from, wire::RefuseReason::ProtocolVersion, "protocol version mismatch: update the client");
    return;
  }
  if (m.library_hash() != library_.content_hash) {
    char text[256];
    std::snprintf(text, sizeof text,
                  "motion library differs: yours has hash %016llx, the server's '%s' has %016llx; "
                  "start with the same --motions as the server",
                  static_cast<unsigned long long>(m.library_hash()), library_.name.c_str(),
                  static_cast<unsigned long long>(library_.content_hash));
    send_refuse(from, wire::RefuseReason::Library, text);
    return;
  }
  if (num_players() + static_cast<int>(join_queue_.size()) >= config_.max_players) {
    send_refuse(from, wire::RefuseReason::ServerFull, "server full");
    return;
  }
  const auto* client_key = m.client_key();
  if (client_key == nullptr || client_key->size() != protocol::kSessionKeyBytes) {
    send_refuse(from, wire::RefuseReason::ProtocolVersion, "no session key in the ConnectResponse: update the client");
    return;
  }
  // Verified (the cookie proves the address): queue it, once; admit_joins() takes a few per tick.
  const uint64_t key = endpoint_key(from);
  for (const PendingJoin& j : join_queue_)
    if (j.key == key && same_endpoint(j.endpoint, from)) {  // already waiting: say so, it keeps waiting
      send_refuse(from, wire::RefuseReason::Queued, "waiting to join: the server admits a few players a tick");
      return;
    }
  if (!join_queue_.empty()) ++counters_.joins_deferred;
  PendingJoin join{from, key, m.client_name() ? protocol::printable_name(m.client_name()->string_view()) : std::string(), {}};
  std::copy(client_key->begin(), client_key->end(), join.client_key.begin());
  join_queue_.push_back(std::move(join));
}

void Server::admit_joins(Clock::time_point now) {
  for (int admitted = 0; admitted < config_.max_joins_per_tick && !join_queue_.empty(); ++admitted) {
    PendingJoin join = std::move(join_queue_.front());
    join_queue_.pop_front();
    admit(join, now);
  }
}

void Server::admit(const PendingJoin& join, Clock::time_point now) {
  const protocol::Endpoint& from = join.endpoint;
  Placement spawn;
  if (!find_spawn(spawn)) {
    ++counters_.spawn_refusals;
    send_refuse(from, wire::RefuseReason::NoSpawnPlace,
                "no free spawn place: every place near the spawns is taken by other avatars; try again later");
    return;
  }
  auto p = std::make_unique<Player>();
  p->endpoint = from;
  p->session = next_session_++;
  p->avatar_id = next_avatar_++;
  p->sent_views.set_owner(p->avatar_id);
  p->name = join.name;
  // The session's keys (session_crypto.hpp): ours for this session, the client's from its response.
  const protocol::SessionKeyPair pair = protocol::session_keypair();
  protocol::SessionKeys keys;
  if (!protocol::session_keys_server(pair, join.client_key, keys)) {
    send_refuse(from, wire::RefuseReason::ProtocolVersion, "unusable session key: update the client");
    return;
  }
  p->sealer.set(p->session, keys.send);
  p->opener.set(p->session, keys.receive);
  p->server_public_key = pair.public_key;
  if (terrain_mode_) {
    p->terrain = std::make_unique<terrain::TerrainAvatar>();
    if (!terrain::terrain_avatar_init(*p->terrain, terrain_config_, scene_, spawn.pos_m, spawn.heading_rad)) {
      ++counters_.spawn_refusals;
      send_refuse(from, wire::RefuseReason::NoSpawnPlace, "no ground at the free spawn place: try again later");
      return;
    }
  } else {
    p->avatar = std::make_unique<LookaheadAvatar>(library_, world_, tree_config_, spawn_segment_, spawn);
    // Reserve the spawn at once, so a second player joining this tick keeps clear of it.
    reservations_.add(static_cast<int>(p->avatar_id), library_, spawn_segment_, 0, spawn);
  }
  p->last_heard = now;
  p->tokens = config_.max_packets_per_s;
  p->tokens_at = now;
  send_accept(*p);
  ++counters_.sessions_opened;
  std::fprintf(stderr, "foresight-server: player %u '%s' joined from %s:%u (session %u, %d players)\n",
               p->avatar_id, p->name.c_str(), from.address().to_string().c_str(), from.port(), p->session,
               num_players() + 1);
  by_endpoint_[endpoint_key(from)] = p.get();
  players_.push_back(std::move(p));
}

void Server::on_input(Player& p, const wire::Input& m) {
  // The client holds that snapshot whole: later ones may code its avatars against it.
  p.sent_views.acknowledge(snapshot_archive_, m.ack_snapshot());
  p.echo_client_time_ms = m.client_time_ms();
  const auto* commands = m.commands();
  if (commands == nullptr || commands->size() == 0) return;
  if (commands->size() > static_cast<flatbuffers::uoffset_t>(protocol::kInputRedundancy)) {
    counters_.drops.add(protocol::DropReason::kInvalidInput);
    return;
  }
  // Commands are held directions: the newest one not yet applied is what the player holds now.
  // Older ones in the packet were either applied already or superseded.
  const wire::InputCommand* newest = commands->Get(commands->size() - 1);
  if (p.any_input && static_cast<int32_t>(newest->sequence() - p.last_input_seq) <= 0) return;
  const ControlInput in = protocol::control_input_from_command(*newest);
  if (in.camera_dir != p.input.camera_dir || in.camera_yaw_rad != p.input.camera_yaw_rad ||
      in.crouch != p.input.crouch) {
    p.input = in;
    p.input_changed = true;
  }
  p.last_input_seq = newest->sequence();
  p.any_input = true;
}

// ---------------------------------------------------------------------------------------------
// Sending

void Server::send(std::span<const uint8_t> bytes, const protocol::Endpoint& to) {
  if (socket_.send(bytes, to)) {
    ++counters_.packets_out;
    counters_.bytes_out += bytes.size();
  } else {
    ++counters_.send_failures;
  }
}

void Server::send_refuse(const protocol::Endpoint& to, wire::RefuseReason reason, const std::string& message) {
  auto& fbb = writer_.begin();
  const auto text = fbb.CreateString(message);
  send(writer_.finish(wire::CreateRefuse(fbb, reason, text, library_.content_hash)), to);
  if (reason != wire::RefuseReason::ShuttingDown && reason != wire::RefuseReason::Queued) ++counters_.refused;
}

void Server::send_accept(const Player& p) {
  auto& fbb = writer_.begin();
  const auto scene = fbb.CreateString(scene_.name);
  const auto lib = fbb.CreateString(library_.name);
  const auto key = fbb.CreateVector(p.server_public_key.data(), p.server_public_key.size());
  send(writer_.finish(wire::CreateAccept(fbb, p.session, p.avatar_id, scene, lib, library_.content_hash,
                                         static_cast<uint16_t>(config_.tick_hz),
                                         static_cast<uint16_t>(config_.snapshot_hz), key, scene_hash_,
                                         static_cast<uint32_t>(scene_file_.size()))),
       p.endpoint);
}

void Server::send_scene_part(Player& p, uint32_t offset) {
  if (offset >= scene_file_.size()) {
    counters_.drops.add(protocol::DropReason::kUnexpected);
    return;
  }
  const uint32_t n = std::min<uint32_t>(protocol::kScenePartBytes, static_cast<uint32_t>(scene_file_.size()) - offset);
  auto& fbb = writer_.begin();
  const auto data = fbb.CreateVector(reinterpret_cast<const uint8_t*>(scene_file_.data()) + offset, n);
  send_sealed(p, writer_.finish(wire::CreateScenePart(fbb, scene_hash_, static_cast<uint32_t>(scene_file_.size()),
                                                      offset, data)));
  ++counters_.scene_parts_sent;
}

void Server::send_sealed(Player& p, std::span<const uint8_t> inner) {
  send(p.sealer.seal(seal_writer_, inner), p.endpoint);
}

void Server::send_stats(Player& p) {
  const TickRecord mean = stats_.mean();
  auto& fbb = writer_.begin();
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
  send_sealed(p, writer_.finish(b.Finish()));
}

void Server::send_tree(Player& p) {
  // Only ever the requester's own tree: the session named in the request is the player's.
  if (!p.avatar) return;  // a terrain avatar has none
  send_sealed(p, tree_summary_.write(writer_, p.avatar->tree(), tick_, p.avatar_id));
}

void Server::send_snapshots(Clock::time_point now) {
  snapshot_accumulator_ += static_cast<double>(config_.snapshot_hz) / config_.tick_hz;
  if (snapshot_accumulator_ < 1.0) return;
  snapshot_accumulator_ -= 1.0;
  ++snapshot_tick_;
  snapshot_states_.clear();
  snapshot_terrain_.clear();
  terrain_before_.clear();
  snapshot_positions_.clear();
  // In id order: a client's view (increasing indices into these arrays) is then sorted by id, as
  // the packed avatars want it.
  by_id_.resize(players_.size());
  for (size_t i = 0; i < players_.size(); ++i) by_id_[i] = static_cast<uint32_t>(i);
  std::sort(by_id_.begin(), by_id_.end(),
            [this](uint32_t a, uint32_t b) { return players_[a]->avatar_id < players_[b]->avatar_id; });
  for (uint32_t index : by_id_) {
    const auto& p = players_[index];
    terrain_before_.push_back(static_cast<uint32_t>(snapshot_terrain_.size()));
    snapshot_positions_.push_back(p->terrain ? terrain::terrain_avatar_ground(*p->terrain) : p->avatar->root().pos_m);
    if (p->terrain) {
      collect_terrain_body(*p);
      continue;
    }
    const PlaybackState& s = p->avatar->playback();
    wire::AvatarState a(p->avatar_id, protocol::quantize_mm(s.segment_start.pos_m.x),
                        protocol::quantize_mm(s.segment_start.pos_m.y), s.incoming_transition,
                        static_cast<uint16_t>(s.segment), protocol::quantize_angle(s.segment_start.heading_rad),
                        static_cast<uint8_t>(std::clamp(s.frame, 0, 255)),
                        static_cast<uint8_t>(
                            (p->avatar->tree().node(p->avatar->tree().root()).first_child < 0 ? protocol::kAvatarFallback
                                                                                              : protocol::kAvatarNone) |
                            (p->is_fighter() ? protocol::kAvatarNpc : protocol::kAvatarNone) |
                            (p->is_fighter() && p->fighter->motion.striking() ? protocol::kAvatarStriking
                                                                              : protocol::kAvatarNone)),
                        0);
    snapshot_states_.push_back(a);
  }
  terrain_before_.push_back(static_cast<uint32_t>(snapshot_terrain_.size()));
  snapshot_archive_.start(snapshot_tick_, static_cast<uint32_t>(tick_)).avatars.assign(snapshot_states_.begin(),
                                                                                        snapshot_states_.end());
  collect_fighter_poses();
  const bool interest = config_.interest_radius_m > 0;
  if (interest) interest_grid_.build(snapshot_positions_, config_.interest_radius_m);
  SnapshotFrame frame;
  frame.snapshot = snapshot_tick_;
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
  frame.far_every = config_.far_every;
  frame.archive = &snapshot_archive_;
  snapshot_receivers_.clear();
  for (size_t index = 0; index < by_id_.size(); ++index) {
    Player& p = *players_[by_id_[index]];
    if (p.is_fighter()) continue;
    snapshot_receivers_.push_back({static_cast<uint32_t>(index), p.avatar_id, p.last_input_seq, p.echo_client_time_ms,
                                   &p.endpoint, &p.sealer, &p.sent_views});
  }
  // Clients in parallel on the look-ahead workers, each worker with its own builder and batch.
  workers_->run(static_cast<int>(snapshot_receivers_.size()), [this, &frame](int item, int worker) {
    snapshot_builders_[static_cast<size_t>(worker)]->serve(frame, snapshot_receivers_[static_cast<size_t>(item)],
                                                           socket_);
  });
  for (auto& builder : snapshot_builders_) {
    builder->flush(socket_);
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

void Server::expire(Clock::time_point now) {
  const auto timeout = std::chrono::duration<double>(config_.session_timeout_s);
  for (size_t i = players_.size(); i-- > 0;) {
    if (!players_[i]->is_fighter() && now - players_[i]->last_heard > timeout) {
      std::fprintf(stderr, "foresight-server: player %u timed out\n", players_[i]->avatar_id);
      ++counters_.sessions_timed_out;
      remove_player(i);
    }
  }
}

void Server::remove_player(size_t index) {
  std::fprintf(stderr, "foresight-server: player %u left (%d players)\n", players_[index]->avatar_id,
               num_players() - 1);
  by_endpoint_.erase(endpoint_key(players_[index]->endpoint));
  // Swap with the last: O(1), and the order of the others (which decides who commits first in a
  // tick) stays deterministic.
  std::swap(players_[index], players_.back());
  // Freeing a tree returns about 0.6 MB to the system (~0.2 ms): a crowd leaving at once would
  // stall the tick, so the memory is released a few players per tick (end of run_tick).
  retired_.push_back(std::move(players_.back()));
  players_.pop_back();
}

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

bool Server::find_spawn(Placement& out) const {
  for (const Placement& p : spawn_places_) {
    if (place_is_free_now(p)) {
      out = p;
      return true;
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
  if (spawn_places_.empty()) {
    error = "scene '" + scene_.name + "': no place within 8 m of any spawn fits the avatar's standing body";
    return false;
  }
  return true;
}

void Server::advance(TickRecord& record) {
  // Reservations: every avatar's committed motion as it stands now.
  reservations_.clear();
  for (const auto& p : players_) {
    if (!p->avatar) continue;
    const PlaybackState& s = p->avatar->playback();
    reservations_.add(static_cast<int>(p->avatar_id), library_, s.segment, s.frame, s.segment_start);
  }
  const double fps = library_.clips.empty() ? 30.0 : library_.clips.front().fps;
  const int64_t due = frames_due(tick_, fps, config_.tick_hz) - frames_due(tick_ - 1, fps, config_.tick_hz);
  for (const auto& p : players_) {
    for (int64_t f = 0; f < due && p->avatar; ++f) {
      const ReservationVeto veto(reservations_, library_, static_cast<int>(p->avatar_id),
                                 p->avatar->fallback_segment());
      const AvatarStepResult r = p->avatar->step(&veto);
      if (r.fallback) ++counters_.fallbacks;
      if (r.steered) ++counters_.steered_frames;
      if (r.recovery) ++counters_.recoveries;
      if (r.segment_changed || r.steered) {  // committed: reserve it now for the players deciding after
        const PlaybackState& s = p->avatar->playback();
        reservations_.add(static_cast<int>(p->avatar_id), library_, s.segment, s.frame, s.segment_start);
      }
    }
  }
  animate_fighters(due);
  advance_terrain(record);
}

void Server::grow_trees(Clock::time_point tick_start, Clock::time_point now, TickRecord& record) {
  tree_players_.clear();
  for (const auto& p : players_)
    if (p->avatar) tree_players_.push_back(p.get());
  const size_t n = tree_players_.size();
  if (n == 0) {
    record.tree_size_min = -1;  // no players: not part of the tree figures
    return;
  }
  const double period_ms = 1000.0 / config_.tick_hz;
  // What the tick leaves: the period minus what was spent so far, what the rest of the tick
  // (advance, snapshots) took lately, and the safety margin; capped.
  const double budget_ms = std::clamp(
      period_ms - ms_between(tick_start, now) - tail_ms_estimate_ - config_.tick_safety_margin_ms, 0.0,
      config_.lookahead_budget_ms);
  record.budget_ms = static_cast<float>(budget_ms);
  // Shared by need: a thin tree or a decision coming soon asks for more.
  grow_weight_.resize(n);
  grow_expansions_.assign(n, 0);
  double total = 0;
  for (size_t i = 0; i < n; ++i) {
    const LookaheadAvatar& a = *tree_players_[i]->avatar;
    const int left = library_.graph.segments[static_cast<size_t>(a.playback().segment)].num_frames() - a.playback().frame;
    const double thin = std::clamp(1.0 - a.tree().num_nodes() / 64.0, 0.0, 1.0);
    const double soon = std::clamp(1.0 - left / 15.0, 0.0, 1.0);
    grow_weight_[i] = 1.0 + 2.0 * thin + soon;
    total += grow_weight_[i];
  }
  const int workers = workers_->threads();
  // Each worker spends up to budget_ms in parallel: its avatars' shares add up to its time.
  const double per_weight_ms = budget_ms * workers / total;
  const Clock::time_point end = now + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double, std::milli>(budget_ms));
  // Two pointers captured: the job fits std::function's inline storage (no allocation per tick).
  const struct {
    double per_weight_ms;
    Clock::time_point end;
  } phase{per_weight_ms, end};
  workers_->run(static_cast<int>(n), [this, &phase](int item, int) {
    Player& p = *tree_players_[static_cast<size_t>(item)];
    LookaheadAvatar& a = *p.avatar;
    GrowBudget budget;
    const bool timed = config_.expansions_per_avatar <= 0;
    if (timed) {
      double slice_ms = phase.per_weight_ms * grow_weight_[static_cast<size_t>(item)];
      if (config_.lookahead_avatar_max_ms > 0) slice_ms = std::min(slice_ms, config_.lookahead_avatar_max_ms);
      const auto slice = std::chrono::duration<double, std::milli>(slice_ms);
      budget = GrowBudget::until(std::min(phase.end, Clock::now() + std::chrono::duration_cast<Clock::duration>(slice)));
    } else {
      budget = GrowBudget::expansions(config_.expansions_per_avatar);
    }
    // Command matching measures v_k from where the avatar stands and strategies 1 and 4 re-sort
    // the leaves (about 25 ns a node): at once when the command changes, just before a decision,
    // and otherwise every resort_interval_ticks (1 = every tick, as the lab's replay does every
    // frame). On the look-ahead threads, never per packet. The periodic re-sort is the first
    // thing dropped when the tick runs late.
    const int frames_left = library_.graph.segments[static_cast<size_t>(a.playback().segment)].num_frames() -
                            a.playback().frame;
    const bool periodic =
        (tick_ + p.avatar_id) % config_.resort_interval_ticks == 0 && (!timed || Clock::now() < phase.end);
    if (p.input_changed || frames_left <= 1 || periodic) {
      a.set_input(p.input);
      p.input_changed = false;
    }
    grow_expansions_[static_cast<size_t>(item)] = a.grow(budget).expansions;
  });
  record.lookahead_ms = static_cast<float>(ms_between(now, Clock::now()));
  int64_t expansions = 0;
  int64_t nodes = 0;
  int min_nodes = INT32_MAX;
  for (size_t i = 0; i < n; ++i) {
    expansions += grow_expansions_[i];
    const int size = tree_players_[i]->avatar->tree().num_nodes();
    nodes += size;
    min_nodes = std::min(min_nodes, size);
  }
  record.expansions = expansions;
  record.tree_size_mean = static_cast<float>(static_cast<double>(nodes) / static_cast<double>(n));
  record.tree_size_min = min_nodes;
}

void Server::check_contacts() {
  // Independent of the reservations and the terrain veto: do two avatars' bodies (this frame's
  // volumes; a terrain body's pelvis circle) overlap?
  contact_bodies_.clear();
  for (const auto& p : players_) {
    if (p->terrain) {
      contact_bodies_.push_back({terrain::terrain_avatar_ground(*p->terrain), terrain::kTerrainBodyRadius_m});
    } else {
      const PlaybackState& s = p->avatar->playback();
      contact_bodies_.push_back(place(library_.volumes(s.segment)[static_cast<size_t>(s.frame)], s.segment_start));
    }
  }
  if (any_footprints_overlap(contact_bodies_)) ++counters_.avatar_contacts;
}

}  // namespace foresight::server

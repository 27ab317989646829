#include "transport/client_connection.hpp"

#include "protocol/input_packet.hpp"
#include "protocol/quantize.hpp"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <utility>

namespace foresight::protocol {

namespace {

/// Serial-number order (RFC 1982): ticks, sequences and client times wrap at 2^32.
bool newer(uint32_t a, uint32_t b) { return static_cast<int32_t>(a - b) > 0; }

double ms_between(ClientConnection::TimePoint from, ClientConnection::TimePoint to) {
  return std::chrono::duration<double, std::milli>(to - from).count();
}

std::string endpoint_text(const Endpoint& e) {
  return e.address().to_string() + ":" + std::to_string(e.port());
}

std::string hash_text(uint64_t hash) {
  char buf[24];
  std::snprintf(buf, sizeof(buf), "%016" PRIx64, hash);
  return buf;
}

bool same_payload(const wire::InputCommand& a, const wire::InputCommand& b) {
  return a.camera_yaw() == b.camera_yaw() && a.dir_x() == b.dir_x() && a.dir_y() == b.dir_y() &&
         a.buttons() == b.buttons();
}

bool is_stop(const wire::InputCommand& c) {
  return c.dir_x() == 0 && c.dir_y() == 0 && c.buttons() == wire::Buttons::NONE;
}

}  // namespace

const char* client_state_name(ClientState state) {
  switch (state) {
    case ClientState::kConnecting: return "connecting";
    case ClientState::kConnected: return "connected";
    case ClientState::kRefused: return "refused";
    case ClientState::kTimedOut: return "timed_out";
    case ClientState::kServerGone: return "server_gone";
    case ClientState::kClosed: return "closed";
  }
  return "unknown";
}

ClientConnection::ClientConnection(const ClientConfig& config) : config_(config) {
  avatars_.reserve(config_.reserve_avatars);
  decoded_.reserve(config_.reserve_avatars);
  history_.reserve(config_.reserve_avatars);
  fighters_.reserve(16);
  terrain_bodies_.reserve(config_.reserve_avatars);
  if (config_.impairment.active()) {
    up_ = std::make_unique<ImpairedQueue>(config_.impairment, 1);
    down_ = std::make_unique<ImpairedQueue>(config_.impairment, 2);
  }
  new_strike_events_.reserve(16);
  tree_.end_m.reserve(kMaxTreeSamples);
  tree_.parent.reserve(kMaxTreeSamples);
  tree_.depth.reserve(kMaxTreeSamples);
  tree_.chosen.reserve(kMaxTreeSamples);
  tree_.segment.reserve(kMaxTreeSamples);
  tree_.start_heading_rad.reserve(kMaxTreeSamples);
}

bool ClientConnection::start(const Endpoint& server, uint64_t library_hash, std::string name,
                             TimePoint now) {
  now_ = now;
  if (!socket_.is_open()) {
    std::string error;
    // An IPv6 server needs an IPv6 socket, whatever the configured (IPv4 "any") address.
    const bool v6 = server.address().is_v6() && config_.bind_address == "0.0.0.0";
    if (!socket_.open(v6 ? "::" : config_.bind_address, 0, error)) {
      set_state(ClientState::kClosed, "cannot open a UDP socket: " + error);
      return false;
    }
  }
  server_ = server;
  library_hash_ = library_hash;
  name_ = std::move(name);
  cookie_size_ = 0;
  started_at_ = handshake_since_ = now;
  handshake_timeout_ = config_.handshake_timeout;
  accepted_at_ = last_heard_ = now;
  accept_ = {};
  refuse_ = {};
  held_ = {};
  num_commands_ = 0;
  sequence_ = ack_input_ = payload_since_ = 0;
  key_pair_ = session_keypair();
  sealer_ = Sealer{};
  opener_ = Opener{};
  has_snapshot_ = has_own_avatar_ = false;
  snapshot_parts_seen_.reset();
  history_.clear();
  acked_snapshot_ = ack_sent_ = 0;
  avatars_.clear();
  fighters_.clear();
  terrain_bodies_.clear();
  new_strike_events_.clear();
  last_strike_sequence_ = 0;  // a new session numbers its events from 1 again
  tree_count_ = 0;
  newest_echo_ms_ = 0;
  sent_times_.fill({});
  set_state(ClientState::kConnecting, "connecting to " + endpoint_text(server_) + " ...");
  send_handshake(now);
  return true;
}

// ---------------------------------------------------------------------------------------------
// Receiving.

void ClientConnection::poll(TimePoint now) {
  now_ = now;
  if (!socket_.is_open()) return;
  for (int i = 0; i < config_.max_datagrams_per_poll; ++i) {
    const ptrdiff_t n = socket_.receive(receive_buffer_, from_);
    if (n < 0) break;
    // The socket is not connected: anyone may send to it. Only the server's datagrams count.
    if (from_ != server_) {
      drops_.add(DropReason::kUnexpected);
      continue;
    }
    if (static_cast<size_t>(n) > receive_buffer_.size()) {  // cut off by the buffer: never on the wire
      bytes_received_ += static_cast<uint64_t>(n);
      ++packets_received_;
      drops_.add(DropReason::kTooLarge);
      continue;
    }
    const std::span<const uint8_t> datagram(receive_buffer_.data(), static_cast<size_t>(n));
    if (down_) {
      down_->push(datagram, now);  // on the (impaired) wire a while longer
    } else {
      take_datagram(datagram, now);
    }
  }
  if (down_) down_->release(now, [this, now](std::span<const uint8_t> d) { take_datagram(d, now); });
}

void ClientConnection::take_datagram(std::span<const uint8_t> datagram, TimePoint now) {
  bytes_received_ += datagram.size();
  ++packets_received_;
  if (datagram.size() > kMaxDatagramBytes) {
    drops_.add(DropReason::kTooLarge);
    return;
  }
  DropReason reason = DropReason::kNone;
  const wire::Packet* packet = packet_read(datagram, reason);
  if (packet == nullptr) {
    drops_.add(reason);
    return;
  }
  handle(*packet, now);
}

void ClientConnection::handle(const wire::Packet& packet, TimePoint now, bool sealed) {
  const bool connecting = state_ == ClientState::kConnecting;
  const bool connected = state_ == ClientState::kConnected;
  // After the Accept, only our session's sealed messages count (and resent Accepts).
  const wire::Message type = packet.message_type();
  if (connected && !sealed && type != wire::Message::Accept && type != wire::Message::Sealed) {
    drops_.add(DropReason::kUnauthenticated);
    return;
  }
  switch (type) {
    case wire::Message::Sealed: {
      if (!connected || sealed) break;
      DropReason reason = DropReason::kNone;
      const wire::Packet* inner = opener_.open(*packet.message_as_Sealed(), reason);
      if (inner == nullptr) {
        drops_.add(reason);
        return;
      }
      handle(*inner, now, true);
      return;
    }
    case wire::Message::Challenge:
      if (!connecting) break;
      on_challenge(*packet.message_as_Challenge(), now);
      return;
    case wire::Message::Accept:
      if (connecting) {
        on_accept(*packet.message_as_Accept(), now);
        return;
      }
      // The server answers each resent ConnectResponse: later copies of our Accept are harmless,
      // and are not taken as hearing from the server: they travel in the clear and session ids
      // are small sequential numbers, so anyone able to send from the server's address could
      // keep a client from noticing its server is gone. Only sealed messages count.
      if (connected && packet.message_as_Accept()->session() == accept_.session) return;
      break;
    case wire::Message::Refuse:
      if (connecting && packet.message_as_Refuse()->reason() == wire::RefuseReason::Queued) {
        handshake_since_ = now;  // verified and queued: the handshake's timeout starts again
        status_ = "connecting to " + endpoint_text(server_) + " (queued to join) ...";
        return;
      }
      if (connecting) {
        on_refuse(*packet.message_as_Refuse());
        return;
      }
      if (connected && packet.message_as_Refuse()->reason() == wire::RefuseReason::ShuttingDown) {
        set_state(ClientState::kServerGone, "the server is shutting down");
        return;
      }
      break;
    case wire::Message::Snapshot:
      if (!connected) break;
      last_heard_ = now;
      on_snapshot(*packet.message_as_Snapshot(), now);
      return;
    case wire::Message::ServerStats:
      if (!connected) break;
      last_heard_ = now;
      on_stats(*packet.message_as_ServerStats());
      return;
    case wire::Message::TreeSummary:
      if (!connected) break;
      last_heard_ = now;
      on_tree(*packet.message_as_TreeSummary());
      return;
    case wire::Message::ScenePart:
      if (!connected) break;
      last_heard_ = now;
      scene_download_.add(*packet.message_as_ScenePart());  // out-of-order or repeated parts are ignored
      return;
    case wire::Message::Disconnect:
      if (connected && packet.message_as_Disconnect()->session() == accept_.session) {
        set_state(ClientState::kServerGone, "the server ended the session");
        return;
      }
      break;
    default:
      break;
  }
  drops_.add(DropReason::kUnexpected);
}

void ClientConnection::on_challenge(const wire::Challenge& m, TimePoint now) {
  const auto* cookie = m.cookie();
  if (cookie == nullptr || cookie->size() == 0 || cookie->size() > cookie_.size()) {
    drops_.add(DropReason::kInvalidInput);
    return;
  }
  // Repeats of the same Challenge (one per resent ConnectRequest) change nothing.
  if (cookie_size_ == cookie->size() && std::equal(cookie->begin(), cookie->end(), cookie_.begin())) {
    return;
  }
  // The first challenge measures the round trip (at most: the first request may have been lost):
  // the rest of the handshake gets four of them, and never less than handshake_timeout. Over a
  // link with a second of latency each way the handshake needs two round trips, more than a
  // fixed 5 s allows once a packet is lost (issue 19).
  if (cookie_size_ == 0) {
    const auto rtt = std::chrono::duration_cast<std::chrono::milliseconds>(now - started_at_);
    handshake_timeout_ = std::max(config_.handshake_timeout, 4 * rtt);
    handshake_since_ = now;
  }
  std::copy(cookie->begin(), cookie->end(), cookie_.begin());
  cookie_size_ = cookie->size();
  status_ = "connecting to " + endpoint_text(server_) + " (challenge received) ...";
  send_handshake(now);
}

void ClientConnection::on_accept(const wire::Accept& m, TimePoint now) {
  SessionKeys keys;
  const auto* server_key = m.server_key();
  if (server_key == nullptr || !session_keys_client(key_pair_, {server_key->data(), server_key->size()}, keys)) {
    refuse_ = {wire::RefuseReason::ProtocolVersion, "no session key in the Accept", 0};
    set_state(ClientState::kRefused, "refused: the server sent no session key (protocol version " +
                                         std::to_string(kProtocolVersion) + " needs one)");
    return;
  }
  sealer_.set(m.session(), keys.send);
  opener_.set(m.session(), keys.receive);
  accept_.session = m.session();
  accept_.avatar = m.avatar();
  accept_.scene = m.scene() ? m.scene()->str() : std::string();
  accept_.library_name = m.library_name() ? m.library_name()->str() : std::string();
  accept_.library_hash = m.library_hash();
  accept_.tick_hz = m.tick_hz();
  accept_.snapshot_hz = m.snapshot_hz();
  accept_.scene_hash = m.scene_hash();
  accept_.scene_bytes = m.scene_bytes();
  scene_download_.start(accept_.scene_hash, accept_.scene_bytes);
  accepted_at_ = last_heard_ = now;
  // The first Input goes out with the next flush(), whatever the input interval.
  last_input_sent_ = last_packet_sent_ = now - std::chrono::hours(1);
  set_state(ClientState::kConnected,
            "connected to " + endpoint_text(server_) + ": session " + std::to_string(accept_.session) +
                ", avatar " + std::to_string(accept_.avatar) + ", scene '" + accept_.scene +
                "', " + std::to_string(accept_.tick_hz) + " Hz tick, " +
                std::to_string(accept_.snapshot_hz) + " Hz snapshots");
}

void ClientConnection::on_refuse(const wire::Refuse& m) {
  refuse_.reason = m.reason();
  refuse_.message = m.message() ? m.message()->str() : std::string();
  refuse_.server_library_hash = m.server_library_hash();
  std::string text = "refused by " + endpoint_text(server_) + " (" +
                     wire::EnumNameRefuseReason(refuse_.reason) + ")";
  if (!refuse_.message.empty()) text += ": " + refuse_.message;
  switch (refuse_.reason) {
    case wire::RefuseReason::Library:
      // The server's own message usually names both hashes already; add them when it does not.
      if (refuse_.message.find(hash_text(library_hash_)) == std::string::npos) {
        text += " [our motion library " + hash_text(library_hash_) + ", the server's " +
                hash_text(refuse_.server_library_hash) +
                ": run both with the same library (--motions DIR or the built-in default)]";
      }
      break;
    case wire::RefuseReason::ProtocolVersion:
      text += " [we speak protocol " + std::to_string(kProtocolVersion) + "]";
      break;
    default:
      break;
  }
  set_state(ClientState::kRefused, std::move(text));
}

void ClientConnection::take_strike_events(std::vector<StrikeEventInfo>& out) {
  out.insert(out.end(), new_strike_events_.begin(), new_strike_events_.end());
  new_strike_events_.clear();
}

void ClientConnection::on_snapshot(const wire::Snapshot& m, TimePoint now) {
  const uint32_t tick = m.tick();
  const int parts = m.parts();
  const int part = m.part();
  if (parts == 0 || part >= parts) {
    drops_.add(DropReason::kInvalidInput);
    return;
  }
  if (has_snapshot_ && tick != snapshot_tick_ && !newer(tick, snapshot_tick_)) return;  // superseded
  if (has_snapshot_ && tick == snapshot_tick_ && parts == snapshot_parts_ &&
      snapshot_parts_seen_.test(static_cast<size_t>(part)))
    return;  // a duplicated datagram
  decoded_.clear();
  if (const AvatarDecodeStatus status = snapshot_avatars(m, history_, decoded_); status != AvatarDecodeStatus::kOk) {
    drops_.add(status == AvatarDecodeStatus::kMissingBaseline ? DropReason::kMissingBaseline : DropReason::kInvalidInput);
    return;
  }
  if (!has_snapshot_ || newer(tick, snapshot_tick_)) {
    if (has_snapshot_) snapshot_interval_ms_.add(ms_between(last_new_tick_at_, now));
    has_snapshot_ = true;
    snapshot_tick_ = tick;
    snapshot_server_ms_ = m.server_time_ms();
    snapshot_parts_ = parts;
    snapshot_parts_seen_.reset();
    avatars_.clear();
    fighters_.clear();
    terrain_bodies_.clear();
    last_new_tick_at_ = now;
    ++snapshot_ticks_;
  } else if (parts != snapshot_parts_) {
    drops_.add(DropReason::kInvalidInput);
    return;
  }
  snapshot_parts_seen_.set(static_cast<size_t>(part));
  ++snapshot_packets_;

  for (const wire::AvatarState& a : decoded_) {
    avatars_.push_back(a);
    if (a.id() == accept_.avatar || (a.flags() & kAvatarYours) != 0) {
      own_avatar_ = a;
      own_avatar_tick_ = tick;
      has_own_avatar_ = true;
    }
  }
  if (snapshot_parts_seen_.count() == static_cast<size_t>(parts)) {
    // Whole: later snapshots may refer to it, so it is what we acknowledge.
    AvatarHistory::Slot& slot = history_.start(tick, 0);
    slot.avatars.assign(avatars_.begin(), avatars_.end());
    const auto by_id = [](const wire::AvatarState& a, const wire::AvatarState& b) { return a.id() < b.id(); };
    if (!std::is_sorted(slot.avatars.begin(), slot.avatars.end(), by_id))  // parts in order: sorted already
      std::sort(slot.avatars.begin(), slot.avatars.end(), by_id);
    slot.usable = true;
    acked_snapshot_ = tick;
  }
  if (const auto* list = m.fighters()) {
    for (const wire::FighterPose* f : *list) {
      const auto* rotations = f->rotations();
      if (rotations == nullptr || rotations->size() > kMaxFighterJoints) {
        drops_.add(DropReason::kInvalidInput);
        continue;
      }
      FighterPoseState& out = fighters_.emplace_back();
      out.avatar = f->avatar();
      out.morphology = f->morphology();
      out.pelvis_m = vec3(dequantize_mm(f->pelvis_x_mm()), dequantize_mm(f->pelvis_y_mm()), dequantize_mm(f->pelvis_z_mm()));
      out.num_joints = static_cast<uint16_t>(rotations->size());
      std::copy(rotations->begin(), rotations->end(), out.rotations.begin());
    }
  }
  if (const auto* list = m.terrain_bodies()) {
    for (const wire::TerrainBody* b : *list) {
      TerrainBodyState& out = terrain_bodies_.emplace_back();
      out.avatar = b->avatar();
      out.pelvis_m = vec3(dequantize_mm(b->pelvis_x_mm()), dequantize_mm(b->pelvis_y_mm()), dequantize_mm(b->pelvis_z_mm()));
      out.heading_rad = dequantize_angle(b->heading());
      out.status = b->status();
      out.flags = b->flags();
      for (size_t i = 0; i < out.angles_rad.size(); ++i)
        out.angles_rad[i] = static_cast<float>(b->angles()->Get(static_cast<flatbuffers::uoffset_t>(i))) * kTerrainAngleUnitRad;
    }
  }
  if (const auto* list = m.events()) {
    for (const wire::StrikeEventState* e : *list) {
      if (last_strike_sequence_ != 0 && !newer(e->sequence(), last_strike_sequence_)) continue;
      new_strike_events_.push_back({e->sequence(), e->fighter(), e->target(),
                                    vec3(dequantize_mm(e->x_mm()), dequantize_mm(e->y_mm()), dequantize_mm(e->z_mm())),
                                    static_cast<float>(e->miss_mm()) * 0.001f, e->hit(), e->kick()});
      last_strike_sequence_ = e->sequence();
    }
  }
  if (newer(m.ack_input(), ack_input_)) ack_input_ = m.ack_input();

  // One round-trip sample per newly echoed client time: later snapshots repeat the echo until
  // the server receives our next packet, and would only measure how long we were silent.
  const uint32_t echo = m.echo_client_time_ms();
  if (echo != 0 && (newest_echo_ms_ == 0 || newer(echo, newest_echo_ms_))) {
    newest_echo_ms_ = echo;
    double rtt = ms_between(started_at_, now) + 1.0 - static_cast<double>(echo);  // ms resolution
    for (const SentTime& s : sent_times_) {
      if (s.client_time_ms == echo) {
        rtt = ms_between(s.at, now);  // exact, when the packet is still in the ring
        break;
      }
    }
    last_rtt_ms_ = std::max(rtt, 0.0);
    rtt_ms_.add(last_rtt_ms_);
  }
}

void ClientConnection::on_stats(const wire::ServerStats& m) {
  stats_.tick = m.tick();
  stats_.players = m.players();
  stats_.tick_hz = m.tick_hz();
  stats_.tick_ms_p50 = m.tick_ms_p50();
  stats_.tick_ms_p99 = m.tick_ms_p99();
  stats_.tick_ms_max = m.tick_ms_max();
  stats_.overruns = m.overruns();
  stats_.budget_ms_mean = m.budget_ms_mean();
  stats_.lookahead_ms_mean = m.lookahead_ms_mean();
  stats_.expansions_per_tick_mean = m.expansions_per_tick_mean();
  stats_.tree_size_mean = m.tree_size_mean();
  stats_.tree_size_min = m.tree_size_min();
  stats_.packets_in = m.packets_in();
  stats_.packets_dropped = m.packets_dropped();
  stats_.avatar_contacts = m.avatar_contacts();
  ++stats_count_;
}

void ClientConnection::on_tree(const wire::TreeSummary& m) {
  const auto* sampled = m.sampled();
  const size_t n = sampled ? sampled->size() : 0;
  if (n > kMaxTreeSamples) {
    drops_.add(DropReason::kInvalidInput);
    return;
  }
  // A parent must come before its child: drawing walks the arrays once.
  for (size_t i = 0; i < n; ++i) {
    const uint16_t parent = sampled->Get(static_cast<flatbuffers::uoffset_t>(i))->parent();
    if (parent != kTreeNoParent && parent >= i) {
      drops_.add(DropReason::kInvalidInput);
      return;
    }
  }
  tree_.tick = m.tick();
  tree_.avatar = m.avatar();
  tree_.nodes = m.nodes();
  tree_.origin_m = vec2(dequantize_mm(m.origin_x_mm()), dequantize_mm(m.origin_z_mm()));
  tree_.chosen_child_end_m =
      vec2(dequantize_mm(m.chosen_child_end_x_mm()), dequantize_mm(m.chosen_child_end_z_mm()));
  tree_.end_m.resize(n);
  tree_.parent.resize(n);
  tree_.depth.resize(n);
  tree_.chosen.resize(n);
  tree_.segment.resize(n);
  tree_.start_heading_rad.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const wire::TreeNodeSample* s = sampled->Get(static_cast<flatbuffers::uoffset_t>(i));
    tree_.end_m[i] = tree_.origin_m + 0.01f * vec2(static_cast<float>(s->dx_cm()), static_cast<float>(s->dz_cm()));
    tree_.parent[i] = s->parent();
    tree_.depth[i] = s->depth();
    tree_.chosen[i] = (s->flags() & kTreeNodeChosen) != 0 ? 1 : 0;
    tree_.segment[i] = s->segment();
    tree_.start_heading_rad[i] = dequantize_angle(s->start_heading());
  }
  ++tree_count_;
}

// ---------------------------------------------------------------------------------------------
// Sending.

void ClientConnection::flush(TimePoint now) {
  now_ = now;
  flush_messages(now);
  release_sends(now);
}

void ClientConnection::release_sends(TimePoint now) {
  if (up_) up_->release(now, [this](std::span<const uint8_t> d) { send_now(d); });
}

void ClientConnection::flush_messages(TimePoint now) {
  if (state_ == ClientState::kConnecting) {
    if (now - handshake_since_ >= handshake_timeout_) {
      set_state(ClientState::kTimedOut,
                "no answer from " + endpoint_text(server_) + " within " +
                    std::to_string(handshake_timeout_.count()) + " ms" +
                    (cookie_size_ ? " after its challenge" : " (is the server running?)"));
      return;
    }
    if (now >= next_handshake_send_) send_handshake(now);
    return;
  }
  if (state_ != ClientState::kConnected) return;
  if (now - last_heard_ >= config_.server_timeout) {
    set_state(ClientState::kServerGone, "nothing heard from " + endpoint_text(server_) + " for " +
                                            std::to_string(config_.server_timeout.count()) + " ms");
    return;
  }
  send_input(now);
}

void ClientConnection::send_handshake(TimePoint now) {
  if (cookie_size_ == 0) {
    send(write_connect_request(writer_, library_hash_, name_));
  } else {
    send(write_connect_response(writer_, library_hash_, {cookie_.data(), cookie_size_}, name_, key_pair_.public_key));
  }
  next_handshake_send_ = now + config_.handshake_resend;
}

void ClientConnection::send_input(TimePoint now) {
  const wire::InputCommand next = input_command_from(held_, sequence_ + 1);
  const bool same = num_commands_ > 0 && same_payload(next, commands_[static_cast<size_t>(num_commands_ - 1)]);
  // Idle once the server has applied "stop" (any command of this run of stops): waiting for the
  // newest one to be acknowledged would never end when the round trip is longer than a frame.
  const bool idle = same && is_stop(next) && !newer(payload_since_, ack_input_);
  const uint32_t time_ms = client_time_ms(now);
  if (idle) {
    if (acked_snapshot_ != ack_sent_) {
      // An Input without commands: the acknowledgement the server codes our snapshots against.
      remember_send_time(time_ms, now);
      send(write_input(writer_, accept_.session, acked_snapshot_, time_ms, {}));
      ack_sent_ = acked_snapshot_;
      last_packet_sent_ = now;
    } else if (now - last_packet_sent_ >= config_.heartbeat_interval) {
      remember_send_time(time_ms, now);
      send(write_heartbeat(writer_, accept_.session, time_ms));
      last_packet_sent_ = now;
    }
    return;
  }
  if (now - last_input_sent_ < config_.min_input_interval) return;
  ++sequence_;
  if (!same) payload_since_ = sequence_;
  if (num_commands_ == kInputRedundancy) {
    std::move(commands_.begin() + 1, commands_.end(), commands_.begin());
    --num_commands_;
  }
  commands_[static_cast<size_t>(num_commands_++)] = next;
  remember_send_time(time_ms, now);
  send(write_input(writer_, accept_.session, acked_snapshot_, time_ms,
                   {commands_.data(), static_cast<size_t>(num_commands_)}));
  ack_sent_ = acked_snapshot_;
  ++inputs_sent_;
  last_input_sent_ = last_packet_sent_ = now;
}

void ClientConnection::set_input(const ControlInput& input) {
  held_ = input;
  if (!std::isfinite(held_.camera_yaw_rad)) held_.camera_yaw_rad = 0.0f;
  if (!std::isfinite(held_.camera_dir.x) || !std::isfinite(held_.camera_dir.y)) {
    held_.camera_dir = vec2(0.0f);
  }
  const float len2 = glm::dot(held_.camera_dir, held_.camera_dir);
  if (len2 > 1.0f) held_.camera_dir /= std::sqrt(len2);
}

void ClientConnection::request_stats() {
  if (state_ == ClientState::kConnected) send(write_stats_request(writer_, accept_.session));
}

void ClientConnection::request_tree() {
  if (state_ == ClientState::kConnected) send(write_tree_request(writer_, accept_.session));
}

void ClientConnection::request_scene_part() {
  if (state_ == ClientState::kConnected && scene_download_.started() && !scene_download_.complete())
    send(write_scene_request(writer_, accept_.session, scene_download_.next_offset()));
}

void ClientConnection::disconnect() {
  if (state_ == ClientState::kConnected) {
    // Not acknowledged: a few copies make a lost one unlikely to leave a ghost until the timeout.
    for (int i = 0; i < 3; ++i) send(write_disconnect(writer_, accept_.session));
    // Nobody flushes a closed connection: what is still on the impaired wire goes now.
    release_sends(TimePoint::max());
  }
  if (state_ == ClientState::kConnected || state_ == ClientState::kConnecting) {
    set_state(ClientState::kClosed, "disconnected");
  }
}

void ClientConnection::send(std::span<const uint8_t> datagram) {
  if (sealer_.ready()) datagram = sealer_.seal(seal_writer_, datagram);  // a session message
  if (up_) {
    up_->push(datagram, now_);  // sent by a later flush(), when due
  } else {
    send_now(datagram);
  }
}

void ClientConnection::send_now(std::span<const uint8_t> datagram) {
  if (socket_.send(datagram, server_)) {
    bytes_sent_ += datagram.size();
  } else {
    ++send_failures_;
  }
}

void ClientConnection::remember_send_time(uint32_t client_time_ms, TimePoint at) {
  sent_times_[next_sent_time_] = {client_time_ms, at};
  next_sent_time_ = (next_sent_time_ + 1) % sent_times_.size();
}

void ClientConnection::set_state(ClientState state, std::string message) {
  state_ = state;
  status_ = std::move(message);
}

uint32_t ClientConnection::client_time_ms(TimePoint now) const {
  // +1: an echo of 0 means "nothing received yet" on the wire.
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(now - started_at_).count();
  return static_cast<uint32_t>(ms + 1);
}

}  // namespace foresight::protocol

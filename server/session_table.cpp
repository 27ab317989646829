#include "session_table.hpp"

#include "protocol/player_name.hpp"
#include "server_counters.hpp"

#include <algorithm>
#include <array>
#include <cstdio>

namespace foresight::server {

namespace {

bool same_endpoint(const protocol::Endpoint& a, const protocol::Endpoint& b) {
  return a.address() == b.address() && a.port() == b.port();
}

// A hash key for the session table (IPv4: exact; IPv6: hashed, confirmed by same_endpoint).
uint64_t endpoint_key(const protocol::Endpoint& e) {
  std::array<uint8_t, 16> storage;
  const auto bytes = protocol::endpoint_address_bytes(e, storage);
  uint64_t h = 1469598103934665603ull;  // FNV-1a
  for (uint8_t b : bytes) h = (h ^ b) * 1099511628211ull;
  return (h << 16) ^ e.port();
}

uint64_t seconds_of(Clock::time_point now) {
  return static_cast<uint64_t>(std::chrono::duration_cast<std::chrono::seconds>(now.time_since_epoch()).count());
}

}  // namespace

SessionTable::SessionTable(ServerCounters& counters) : counters_(counters) {}

bool SessionTable::open(const std::string& bind_address, uint16_t port, const SessionSettings& settings,
                        std::string& error) {
  settings_ = settings;
  if (!socket_.open(bind_address, port, error)) return false;
  sessions_.reserve(static_cast<size_t>(std::max(settings_.max_players, 0)));
  return true;
}

// ---------------------------------------------------------------------------------------------
// Receiving

void SessionTable::receive(Clock::time_point now, SessionEvents& events) {
  // Bounded: a flood cannot keep the tick in here (what is left waits for the next tick). Taken
  // in recvmmsg batches: at 1000 players that is 1000 inputs a tick.
  for (size_t budget = 20000; budget > 0;) {
    const size_t taken = inbox_.receive(socket_);
    for (size_t i = 0; i < taken; ++i) {
      const std::span<const uint8_t> bytes = inbox_.datagram(i);
      ++counters_.packets_in;
      counters_.bytes_in += bytes.size();
      protocol::DropReason reason;
      const wire::Packet* packet = protocol::packet_read(bytes, reason);
      if (packet == nullptr) {
        counters_.drops.add(reason);
        continue;
      }
      handle(inbox_.from(i), *packet, bytes.size(), now, events);
    }
    if (taken < protocol::DatagramInbox::kCapacity) break;
    budget -= std::min(budget, taken);
  }
}

Handle SessionTable::find(const protocol::Endpoint& from) const {
  const auto it = by_endpoint_.find(endpoint_key(from));
  if (it == by_endpoint_.end()) return {};
  const Session* s = sessions_.get(it->second);
  return s != nullptr && same_endpoint(s->endpoint, from) ? it->second : Handle{};
}

void SessionTable::handle(const protocol::Endpoint& from, const wire::Packet& packet, size_t bytes,
                          Clock::time_point now, SessionEvents& events) {
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
  // A session's message: the sender must have one.
  const Handle h = find(from);
  Session* s = sessions_.get(h);
  if (s == nullptr) {
    counters_.drops.add(protocol::DropReason::kUnexpected);
    return;
  }
  protocol::DropReason reason = protocol::DropReason::kNone;
  const wire::Packet* inner = s->opener.open(*packet.message_as_Sealed(), reason);
  if (inner == nullptr) {
    counters_.drops.add(reason);  // forged, corrupted, another session's, or replayed
    return;
  }
  // Token bucket: max_packets_per_s sustained, one second's worth of burst. Charged only for
  // what the player really sent: charged before opening, datagrams forged with the player's
  // address spent its allowance and its own inputs were dropped (issue 19). Opening is a few
  // hundred nanoseconds, and receive() takes a bounded number of datagrams a tick.
  const double rate = settings_.max_packets_per_s;
  s->tokens = std::min(rate, s->tokens + rate * std::chrono::duration<double>(now - s->tokens_at).count());
  s->tokens_at = now;
  if (s->tokens < 1.0) {
    counters_.drops.add(protocol::DropReason::kRateLimited);
    return;
  }
  s->tokens -= 1.0;
  handle_session(h, *inner, now, events);
}

void SessionTable::handle_session(Handle h, const wire::Packet& packet, Clock::time_point now,
                                  SessionEvents& events) {
  using wire::Message;
  Session& s = *sessions_.get(h);
  uint32_t session = 0;
  if (auto* m = packet.message_as_Input()) session = m->session();
  if (auto* m = packet.message_as_Heartbeat()) session = m->session();
  if (auto* m = packet.message_as_Disconnect()) session = m->session();
  if (auto* m = packet.message_as_StatsRequest()) session = m->session();
  if (auto* m = packet.message_as_TreeRequest()) session = m->session();
  if (auto* m = packet.message_as_SceneRequest()) session = m->session();
  if (s.id != session) {  // sealed by this session's key, yet naming another
    counters_.drops.add(protocol::DropReason::kUnexpected);
    return;
  }
  s.last_heard = now;
  switch (packet.message_type()) {
    case Message::Heartbeat: s.echo_client_time_ms = packet.message_as_Heartbeat()->client_time_ms(); break;
    case Message::Disconnect:
      ++counters_.sessions_closed;
      end(h, events);
      break;
    case Message::Input:
    case Message::StatsRequest:
    case Message::TreeRequest:
    case Message::SceneRequest: events.on_message(s, packet); break;
    default: break;
  }
}

bool SessionTable::answer_unproven() {
  // Every answer to an address not yet proven (a challenge or a refusal) shares one per-tick
  // budget: refusals of a wrong version were sent before it, 1,000 requests got 1,000 answers,
  // an uncapped reflector (issue 19).
  if (challenges_this_tick_ >= settings_.max_challenges_per_tick) {
    ++counters_.challenges_capped;
    return false;
  }
  ++challenges_this_tick_;
  return true;
}

void SessionTable::on_connect_request(const protocol::Endpoint& from, const wire::ConnectRequest& m, size_t bytes,
                                      Clock::time_point now) {
  if (bytes < protocol::kMinConnectRequestBytes) {
    counters_.drops.add(protocol::DropReason::kTooSmall);  // unpadded: could amplify
    return;
  }
  if (!answer_unproven()) return;
  if (m.protocol() != protocol::kProtocolVersion) {
    send_refuse(from, wire::RefuseReason::ProtocolVersion,
                "protocol version " + std::to_string(m.protocol()) + " is not the server's " +
                    std::to_string(protocol::kProtocolVersion) + ": update the client");
    return;
  }
  std::array<uint8_t, 16> storage;
  const protocol::Cookie cookie = cookies_.make(protocol::endpoint_address_bytes(from, storage), from.port(), seconds_of(now));
  auto& fbb = writer_.begin();
  const auto c = fbb.CreateVector(cookie.data(), cookie.size());
  send(writer_.finish(wire::CreateChallenge(fbb, c)), from);
  ++counters_.challenges_sent;
}

void SessionTable::on_connect_response(const protocol::Endpoint& from, const wire::ConnectResponse& m,
                                       Clock::time_point now) {
  if (const Session* existing = sessions_.get(find(from))) {  // our Accept was lost: say it again
    send_accept(*existing);
    return;
  }
  std::array<uint8_t, 16> storage;
  const auto* cookie = m.cookie();
  if (cookie == nullptr || !cookies_.check({cookie->data(), cookie->size()}, protocol::endpoint_address_bytes(from, storage),
                                           from.port(), seconds_of(now))) {
    // The sender's address is unproven: a refusal to it shares the challenges' per-tick budget, so
    // forged responses cannot make the server a reflector either.
    if (answer_unproven())
      send_refuse(from, wire::RefuseReason::BadCookie, "connection cookie wrong or expired: connect again");
    return;
  }
  if (m.protocol() != protocol::kProtocolVersion) {
    send_refuse(from, wire::RefuseReason::ProtocolVersion, "protocol version mismatch: update the client");
    return;
  }
  if (m.library_hash() != settings_.library_hash) {
    char text[256];
    std::snprintf(text, sizeof text,
                  "motion library differs: yours has hash %016llx, the server's '%s' has %016llx; "
                  "start with the same --motions as the server",
                  static_cast<unsigned long long>(m.library_hash()), settings_.library_name.c_str(),
                  static_cast<unsigned long long>(settings_.library_hash));
    send_refuse(from, wire::RefuseReason::Library, text);
    return;
  }
  if (static_cast<int>(sessions_.size() + join_queue_.size()) >= settings_.max_players) {
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

// ---------------------------------------------------------------------------------------------
// Joining and leaving

void SessionTable::admit_joins(Clock::time_point now, SessionEvents& events) {
  for (int admitted = 0; admitted < settings_.max_joins_per_tick && !join_queue_.empty(); ++admitted) {
    PendingJoin join = std::move(join_queue_.front());
    join_queue_.pop_front();
    admit(join, now, events);
  }
}

void SessionTable::admit(PendingJoin& join, Clock::time_point now, SessionEvents& events) {
  Session s;
  s.endpoint = join.endpoint;
  s.name = std::move(join.name);
  // The session's keys (session_crypto.hpp): ours for this session, the client's from its response.
  const protocol::SessionKeyPair pair = protocol::session_keypair();
  protocol::SessionKeys keys;
  if (!protocol::session_keys_server(pair, join.client_key, keys)) {
    send_refuse(s.endpoint, wire::RefuseReason::ProtocolVersion, "unusable session key: update the client");
    return;
  }
  wire::RefuseReason reason = wire::RefuseReason::NoSpawnPlace;
  std::string why;
  if (!events.on_join(s, now, reason, why)) {
    send_refuse(s.endpoint, reason, why);
    return;
  }
  s.id = next_session_++;
  s.sent_views.set_owner(s.avatar_id);
  s.sealer.set(s.id, keys.send);
  s.opener.set(s.id, keys.receive);
  s.server_public_key = pair.public_key;
  s.last_heard = now;
  s.tokens = settings_.max_packets_per_s;
  s.tokens_at = now;
  send_accept(s);
  ++counters_.sessions_opened;
  std::fprintf(stderr, "foresight-server: player %u '%s' joined from %s:%u (session %u, %zu players)\n", s.avatar_id,
               s.name.c_str(), s.endpoint.address().to_string().c_str(), s.endpoint.port(), s.id, sessions_.size() + 1);
  const uint64_t key = endpoint_key(s.endpoint);
  by_endpoint_[key] = sessions_.add(std::move(s));
}

void SessionTable::expire(Clock::time_point now, SessionEvents& events) {
  const auto timeout = std::chrono::duration<double>(settings_.session_timeout_s);
  const auto sessions = sessions_.items();
  for (size_t i = sessions.size(); i-- > 0;) {
    if (now - sessions[i].last_heard > timeout) {
      std::fprintf(stderr, "foresight-server: player %u timed out\n", sessions[i].avatar_id);
      ++counters_.sessions_timed_out;
      end(sessions_.handle_at(i), events);
    }
  }
}

void SessionTable::close_all(SessionEvents& events) {
  while (!sessions_.empty()) {
    const size_t last = sessions_.size() - 1;
    Session& s = sessions_.items()[last];
    for (int copy = 0; copy < 2; ++copy) {
      auto& fbb = writer_.begin();
      const auto text = fbb.CreateString("the server is shutting down");
      send_sealed(s, writer_.finish(wire::CreateRefuse(fbb, wire::RefuseReason::ShuttingDown, text, settings_.library_hash)));
    }
    ++counters_.sessions_closed;
    end(sessions_.handle_at(last), events);
  }
  join_queue_.clear();
}

void SessionTable::end(Handle h, SessionEvents& events) {
  const Session* s = sessions_.get(h);
  if (s == nullptr) return;
  std::fprintf(stderr, "foresight-server: player %u left (%zu players)\n", s->avatar_id, sessions_.size() - 1);
  events.on_leave(*s);
  by_endpoint_.erase(endpoint_key(s->endpoint));
  sessions_.remove(h);
}

// ---------------------------------------------------------------------------------------------
// Sending

void SessionTable::send(std::span<const uint8_t> bytes, const protocol::Endpoint& to) {
  if (socket_.send(bytes, to)) {
    ++counters_.packets_out;
    counters_.bytes_out += bytes.size();
  } else {
    ++counters_.send_failures;
  }
}

void SessionTable::send_sealed(Session& s, std::span<const uint8_t> inner) {
  send(s.sealer.seal(seal_writer_, inner), s.endpoint);
}

void SessionTable::send_refuse(const protocol::Endpoint& to, wire::RefuseReason reason, const std::string& message) {
  auto& fbb = writer_.begin();
  const auto text = fbb.CreateString(message);
  send(writer_.finish(wire::CreateRefuse(fbb, reason, text, settings_.library_hash)), to);
  if (reason != wire::RefuseReason::ShuttingDown && reason != wire::RefuseReason::Queued) ++counters_.refused;
}

void SessionTable::send_accept(const Session& s) {
  auto& fbb = writer_.begin();
  const auto scene = fbb.CreateString(settings_.scene_name);
  const auto lib = fbb.CreateString(settings_.library_name);
  const auto key = fbb.CreateVector(s.server_public_key.data(), s.server_public_key.size());
  send(writer_.finish(wire::CreateAccept(fbb, s.id, s.avatar_id, scene, lib, settings_.library_hash, settings_.tick_hz,
                                         settings_.snapshot_hz, key, settings_.scene_hash, settings_.scene_bytes)),
       s.endpoint);
}

}  // namespace foresight::server

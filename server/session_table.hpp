#pragma once
// The server's side of the connection (the twin of transport/client_connection.hpp): the UDP
// socket, the handshake (cookies, version and library checks, the join queue, the per-tick cap on
// answers to unproven addresses), the sessions' keys (every session message is opened, everything
// sent is sealed), the per-session packet rate limit, and timeouts. It knows nothing of avatars:
// what a session's messages mean, and what a player gets on joining, is the game's
// (SessionEvents, implemented by the Server). docs/PROTOCOL.md has the messages.
#include "clock.hpp"
#include "handle_table.hpp"
#include "protocol/packet.hpp"
#include "protocol/sent_views.hpp"
#include "transport/cookie.hpp"
#include "transport/datagram_batch.hpp"
#include "transport/session_crypto.hpp"
#include "transport/udp_socket.hpp"

#include <chrono>
#include <cstdint>
#include <deque>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

namespace foresight::server {

struct ServerCounters;

struct Session {
  protocol::Endpoint endpoint;
  uint32_t id = 0;
  uint32_t avatar_id = 0;  ///< Its player's avatar (the game sets it when the player joins).
  std::string name;        ///< Printable (protocol::printable_name).
  Clock::time_point last_heard{};
  double tokens = 0;  ///< Packet rate limit (token bucket).
  Clock::time_point tokens_at{};
  bool any_input = false;
  uint32_t last_input_seq = 0;  ///< Newest command applied.
  uint32_t echo_client_time_ms = 0;
  /// Which archived avatars went into the last snapshots sent, and which of those snapshots the
  /// client acknowledged (sent_views.hpp).
  protocol::SentViews sent_views;
  // The session's keys: what we send is sealed, what it sends is opened (session_crypto.hpp).
  protocol::Sealer sealer;
  protocol::Opener opener;
  protocol::SessionKey server_public_key{};
};

/// What the game does for the session table.
class SessionEvents {
 public:
  virtual ~SessionEvents() = default;
  /// A verified join: give the player an avatar (set `s.avatar_id`). False to refuse, with the
  /// reason and text sent to the client.
  virtual bool on_join(Session& s, Clock::time_point now, wire::RefuseReason& reason, std::string& why) = 0;
  /// A session's message (opened, rate-limited, naming this session): Input, Heartbeat,
  /// StatsRequest, TreeRequest or SceneRequest.
  virtual void on_message(Session& s, const wire::Packet& message) = 0;
  /// The session ends (disconnect, timeout, shutdown): take its avatar away.
  virtual void on_leave(const Session& s) = 0;
};

/// What every Accept says about the server, and the limits the handshake enforces.
struct SessionSettings {
  std::string scene_name;
  std::string library_name;
  uint64_t library_hash = 0;
  uint64_t scene_hash = 0;
  uint32_t scene_bytes = 0;
  uint16_t tick_hz = 30;
  uint16_t snapshot_hz = 20;
  int max_players = 64;
  int max_joins_per_tick = 4;
  int max_challenges_per_tick = 64;
  double max_packets_per_s = 120;
  double session_timeout_s = 5;
};

class SessionTable {
 public:
  explicit SessionTable(ServerCounters& counters);
  /// Binds the socket. False with a reason.
  bool open(const std::string& bind_address, uint16_t port, const SessionSettings& settings, std::string& error);
  uint16_t port() const { return socket_.local_port(); }
  protocol::UdpSocket& socket() { return socket_; }

  /// Drains the socket (a bounded number of datagrams): handshakes answered here, sessions'
  /// messages opened and handed to `events`, bad datagrams dropped and counted by reason.
  void receive(Clock::time_point now, SessionEvents& events);
  /// Admits up to max_joins_per_tick queued joins (events.on_join gives each its avatar).
  void admit_joins(Clock::time_point now, SessionEvents& events);
  /// Ends sessions silent for session_timeout_s.
  void expire(Clock::time_point now, SessionEvents& events);
  /// Tells every client the server is shutting down (twice, against a loss) and ends its session.
  void close_all(SessionEvents& events);

  /// The builder for a session's reply; send it with send_sealed(s, writer().finish(...)).
  protocol::PacketWriter& writer() { return writer_; }
  void send_sealed(Session& s, std::span<const uint8_t> inner);

  std::span<Session> sessions() { return sessions_.items(); }
  std::span<const Session> sessions() const { return sessions_.items(); }
  size_t size() const { return sessions_.size(); }
  size_t joins_waiting() const { return join_queue_.size(); }
  /// Where the per-tick cap on answers to unproven addresses starts again (once a tick).
  void start_tick() { challenges_this_tick_ = 0; }

 private:
  struct PendingJoin {
    protocol::Endpoint endpoint;
    uint64_t key = 0;
    std::string name;
    protocol::SessionKey client_key{};
  };

  void handle(const protocol::Endpoint& from, const wire::Packet& packet, size_t bytes, Clock::time_point now,
              SessionEvents& events);
  void on_connect_request(const protocol::Endpoint& from, const wire::ConnectRequest& m, size_t bytes,
                          Clock::time_point now);
  void on_connect_response(const protocol::Endpoint& from, const wire::ConnectResponse& m, Clock::time_point now);
  void handle_session(Handle h, const wire::Packet& packet, Clock::time_point now, SessionEvents& events);
  void admit(PendingJoin& join, Clock::time_point now, SessionEvents& events);
  void end(Handle h, SessionEvents& events);
  bool answer_unproven();  ///< False (counted) when this tick's answers to unproven addresses are spent.
  void send_refuse(const protocol::Endpoint& to, wire::RefuseReason reason, const std::string& message);
  void send_accept(const Session& s);
  void send(std::span<const uint8_t> bytes, const protocol::Endpoint& to);
  Handle find(const protocol::Endpoint& from) const;

  ServerCounters& counters_;
  SessionSettings settings_;
  protocol::UdpSocket socket_;
  protocol::CookieJar cookies_;
  protocol::PacketWriter writer_;
  protocol::PacketWriter seal_writer_;  ///< The Sealed wrapping around what writer_ holds.
  protocol::DatagramInbox inbox_;  ///< What receive() takes from the socket, a batch at a time.
  HandleTable<Session> sessions_;
  std::unordered_map<uint64_t, Handle> by_endpoint_;  ///< endpoint_key -> session
  /// Cookie-verified joins waiting their turn (at most max_players - players long).
  std::deque<PendingJoin> join_queue_;
  uint32_t next_session_ = 1;
  int challenges_this_tick_ = 0;
};

}  // namespace foresight::server

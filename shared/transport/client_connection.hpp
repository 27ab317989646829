#pragma once
// The client side of the protocol (docs/PROTOCOL.md): handshake, Inputs with redundancy,
// Heartbeats, Snapshots, stats. Used by the bots and the interactive client.
//
// Caller-driven and single-threaded: nothing happens between calls, and every call takes the
// time (std::chrono::steady_clock) from the caller, so tests can run minutes in microseconds.
// Per frame the caller does
//   poll(now)        read and handle everything waiting on the socket (may also be called
//                    whenever the socket is readable, for precise arrival times: socket_fd())
//   set_input(...)   the input held this frame
//   flush(now)       timeouts, handshake resends, and at most one Input (or Heartbeat) packet
// or update(now), which is poll(now) then flush(now).
//
// Every datagram goes through packet_read(); one that fails, comes from another address, or is a
// message the client never receives (or not in its state) is dropped and counted by reason.
// Once warm, nothing here allocates per packet: the avatar list is reserved (it grows only when
// a snapshot holds more avatars than ever before), strings are built on state changes only.
#include "world/control_input.hpp"
#include "protocol/avatar_delta.hpp"
#include "transport/histogram.hpp"
#include "transport/impairment.hpp"
#include "transport/session_crypto.hpp"
#include "protocol/packet.hpp"
#include "protocol/protocol.hpp"
#include "transport/scene_transfer.hpp"
#include "transport/udp_socket.hpp"

#include <array>
#include <bitset>
#include <chrono>
#include <memory>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace foresight::protocol {

enum class ClientState : uint8_t {
  kConnecting,  ///< Handshake under way (ConnectRequest / ConnectResponse resent every 250 ms).
  kConnected,   ///< Accepted: sending Inputs, receiving Snapshots.
  kRefused,     ///< The server said no (refuse() tells why). Final.
  kTimedOut,    ///< The handshake got no answer in time. Final.
  kServerGone,  ///< Connected, then silence from the server (or it ended the session). Final.
  kClosed,      ///< Not started, start() failed, or disconnect() was called.
};
const char* client_state_name(ClientState state);

struct ClientConfig {
  std::chrono::milliseconds handshake_resend{250};
  /// From start() to the first Challenge, then from it (or the last "queued") to Accept / Refuse;
  /// after the first Challenge at least four round trips as it measured them.
  std::chrono::milliseconds handshake_timeout{5000};
  std::chrono::milliseconds server_timeout{5000};     ///< Silence after which the server is gone.
  std::chrono::milliseconds heartbeat_interval{1000}; ///< While idle (nothing new to send).
  /// Least time between two Inputs (0: one per flush()). For clients that render faster than
  /// the server needs commands.
  std::chrono::milliseconds min_input_interval{0};
  size_t reserve_avatars = 256;         ///< Initial capacity of the snapshot's avatar list.
  int max_datagrams_per_poll = 4096;    ///< Bounds one poll() under a flood.
  std::string bind_address = "0.0.0.0";  ///< Local address (becomes "::" for an IPv6 server).
  /// Both directions of the link through an impairment layer (impairment.hpp); inactive by default.
  ImpairmentConfig impairment;
};

struct AcceptInfo {
  uint32_t session = 0;
  uint32_t avatar = 0;
  std::string scene;
  std::string library_name;
  uint64_t library_hash = 0;
  uint16_t tick_hz = 0;
  uint16_t snapshot_hz = 0;
  uint64_t scene_hash = 0;   ///< Of the server's scene file (protocol::scene_file_hash).
  uint32_t scene_bytes = 0;  ///< Its size.
};

struct RefuseInfo {
  wire::RefuseReason reason = wire::RefuseReason::None;
  std::string message;
  uint64_t server_library_hash = 0;
};

/// A copy of the newest ServerStats (schema/foresight.fbs documents each field).
struct ServerFigures {
  uint32_t tick = 0;
  uint32_t players = 0;
  uint16_t tick_hz = 0;
  float tick_ms_p50 = 0, tick_ms_p99 = 0, tick_ms_max = 0;
  uint64_t overruns = 0;
  float budget_ms_mean = 0, lookahead_ms_mean = 0, expansions_per_tick_mean = 0;
  float tree_size_mean = 0;
  uint32_t tree_size_min = 0;
  uint64_t packets_in = 0, packets_dropped = 0, avatar_contacts = 0;
};

/// A copy of the newest TreeSummary (schema/foresight.fbs): the player's own feasible motion tree,
/// sampled. Node positions are world ground positions in metres (x, z).
struct TreeView {
  uint32_t tick = 0;
  uint32_t avatar = 0;
  uint32_t nodes = 0;        ///< In the whole tree on the server.
  vec2 origin_m{0.0f};       ///< Where the root segment started.
  vec2 chosen_child_end_m{0.0f};
  std::vector<vec2> end_m;         ///< Per sampled node: its end ground position. [0] = the root.
  std::vector<uint16_t> parent;    ///< Per sampled node: sample index of its parent, kTreeNoParent.
  std::vector<uint8_t> depth;      ///< Per sampled node: depth below the root.
  std::vector<uint8_t> chosen;     ///< Per sampled node: 1 on the branch the tree would select now.
  std::vector<uint16_t> segment;   ///< Per sampled node: its motion-graph segment (unchecked:
                                   ///< the receiver checks it against its library before use).
  std::vector<float> start_heading_rad;  ///< Per sampled node: heading of its start placement.
  /// Where node i's segment starts: its parent's end (the origin for the root).
  Placement start(size_t i) const {
    return {parent[i] == kTreeNoParent ? origin_m : end_m[parent[i]], start_heading_rad[i]};
  }
  size_t size() const { return end_m.size(); }
};

/// An NPC fighter's pose from a snapshot, as sent (rotations still quantised: the client
/// dequantises what it draws).
struct FighterPoseState {
  uint32_t avatar = 0;
  uint8_t morphology = 0;
  vec3 pelvis_m{0.0f};
  uint16_t num_joints = 0;
  std::array<uint32_t, kMaxFighterJoints> rotations{};
};

/// A terrain avatar's body from a snapshot (schema TerrainBody), dequantised: the 18 angles in
/// terrain_body_angles() order (shared/terrain/terrain_body.hpp turns them into a pose).
struct TerrainBodyState {
  uint32_t avatar = 0;
  vec3 pelvis_m{0.0f};
  float heading_rad = 0.0f;
  uint8_t status = 0;  ///< TerrainStepStatus of its last plan.
  uint8_t flags = 0;   ///< TerrainBodyFlags.
  std::array<float, 18> angles_rad{};
};

/// A strike's outcome (schema StrikeEventState), decoded.
struct StrikeEventInfo {
  uint32_t sequence = 0;
  uint32_t fighter = 0;
  uint32_t target = 0;
  vec3 effector_m{0.0f};
  float miss_m = 0.0f;
  bool hit = false;
  bool kick = false;
};

class ClientConnection {
 public:
  using Clock = std::chrono::steady_clock;
  using TimePoint = Clock::time_point;

  explicit ClientConnection(const ClientConfig& config = {});
  ClientConnection(const ClientConnection&) = delete;
  ClientConnection& operator=(const ClientConnection&) = delete;

  /// Opens the socket (once; a restart keeps the port), forgets any previous session and sends
  /// the first ConnectRequest. `library_hash` is MotionLibrary::content_hash of the library the
  /// caller rebuilds poses with. False (state kClosed, status_message() says why) when the socket
  /// cannot be opened.
  bool start(const Endpoint& server, uint64_t library_hash, std::string name, TimePoint now);

  /// Reads and handles every waiting datagram (at most config.max_datagrams_per_poll).
  void poll(TimePoint now);
  /// Timeouts, handshake resends, and while connected one Input (a new command holding the
  /// current input, plus the previous ones up to kInputRedundancy) or, when idle, a Heartbeat
  /// once per heartbeat_interval. Idle: the held input is "stop", equal to the newest command,
  /// and the server has acknowledged that command.
  void flush(TimePoint now);
  void update(TimePoint now) {
    poll(now);
    flush(now);
  }

  /// The input held from now on (sent by the following flush() calls). Clamped to be valid.
  void set_input(const ControlInput& input);
  /// Asks the server for its ServerStats (answered asynchronously: see server_stats_count()).
  void request_stats();
  /// Asks the server for a summary of our feasible motion tree (see tree_count()).
  void request_tree();
  /// Asks for the next part of the server's scene file (call until scene_download().verified();
  /// a request whose answer is lost is simply made again). No-op when complete or not connected.
  void request_scene_part();
  /// The server's scene file as fetched so far (started at the Accept).
  const SceneDownload& scene_download() const { return scene_download_; }
  /// Ends the session: sends Disconnect three times (it is not acknowledged), then kClosed.
  void disconnect();

  ClientState state() const { return state_; }
  bool connected() const { return state_ == ClientState::kConnected; }
  /// For people: what the client is doing, or why it stopped.
  const std::string& status_message() const { return status_; }
  /// Valid once connected (and after, for the record).
  const AcceptInfo& accept() const { return accept_; }
  const RefuseInfo& refuse() const { return refuse_; }
  TimePoint started_at() const { return started_at_; }
  TimePoint accepted_at() const { return accepted_at_; }
  /// The socket's descriptor (for epoll / poll by callers that wait on many clients); -1 closed.
  int socket_fd() { return socket_.native_handle(); }
  uint16_t local_port() const { return socket_.local_port(); }

  // Snapshots. The newest tick seen: its parts are merged as they arrive; a newer tick replaces
  // it; parts of older ticks are ignored.
  bool has_snapshot() const { return has_snapshot_; }
  uint32_t snapshot_tick() const { return snapshot_tick_; }
  /// The server's clock (ms since it started) when it gathered the newest snapshot: snapshot
  /// numbers are each client's own count, so this is what says when two clients saw the same world.
  uint32_t snapshot_server_ms() const { return snapshot_server_ms_; }
  /// The newest snapshot received whole (every part), which Inputs acknowledge; 0 before one.
  uint32_t acked_snapshot() const { return acked_snapshot_; }
  int snapshot_parts() const { return snapshot_parts_; }
  int snapshot_parts_received() const { return static_cast<int>(snapshot_parts_seen_.count()); }
  std::span<const wire::AvatarState> avatars() const { return avatars_; }
  /// The NPC fighters' poses of the newest tick (parts merged as they arrive).
  std::span<const FighterPoseState> fighters() const { return fighters_; }
  /// The terrain avatars' bodies of the newest tick (parts merged as they arrive).
  std::span<const TerrainBodyState> terrain_bodies() const { return terrain_bodies_; }
  /// Strike events not taken before, in sequence order, appended to `out` (each once, however
  /// many snapshots repeat it).
  void take_strike_events(std::vector<StrikeEventInfo>& out);
  /// The client's own avatar as last seen (possibly from an older tick), or nullptr.
  const wire::AvatarState* own_avatar() const { return has_own_avatar_ ? &own_avatar_ : nullptr; }
  uint32_t own_avatar_tick() const { return own_avatar_tick_; }
  /// Snapshot datagrams (parts) taken, and new ticks seen.
  uint64_t snapshot_packets() const { return snapshot_packets_; }
  uint64_t snapshot_ticks() const { return snapshot_ticks_; }

  // Measurements.
  /// Round trip, ms: arrival of a snapshot minus the client time it echoes (one sample per new
  /// echo). Includes the wait at the server for its next snapshot (up to 1 / snapshot_hz).
  const LogHistogram& rtt_ms() const { return rtt_ms_; }
  double last_rtt_ms() const { return last_rtt_ms_; }
  /// Time between the arrivals of consecutive new snapshot ticks, ms.
  const LogHistogram& snapshot_interval_ms() const { return snapshot_interval_ms_; }
  uint64_t bytes_received() const { return bytes_received_; }  ///< Every datagram from the server.
  uint64_t bytes_sent() const { return bytes_sent_; }
  uint64_t packets_received() const { return packets_received_; }
  uint64_t inputs_sent() const { return inputs_sent_; }
  uint64_t send_failures() const { return send_failures_; }
  const DropCounters& drops() const { return drops_; }
  uint32_t input_sequence() const { return sequence_; }   ///< Newest command sent (0: none).
  uint32_t server_ack_input() const { return ack_input_; }
  /// The newest ServerStats, valid when server_stats_count() > 0.
  const ServerFigures& server_stats() const { return stats_; }
  uint64_t server_stats_count() const { return stats_count_; }
  /// The newest TreeSummary, valid when tree_count() > 0.
  const TreeView& tree() const { return tree_; }
  uint64_t tree_count() const { return tree_count_; }

 private:
  /// `sealed`: it came inside a Sealed message of our session (session messages must).
  void handle(const wire::Packet& packet, TimePoint now, bool sealed = false);
  void on_challenge(const wire::Challenge& m, TimePoint now);
  void on_accept(const wire::Accept& m, TimePoint now);
  void on_refuse(const wire::Refuse& m);
  void on_snapshot(const wire::Snapshot& m, TimePoint now);
  void on_stats(const wire::ServerStats& m);
  void on_tree(const wire::TreeSummary& m);
  void send_handshake(TimePoint now);
  void send_input(TimePoint now);
  void send(std::span<const uint8_t> datagram);
  void flush_messages(TimePoint now);
  void release_sends(TimePoint now);
  void send_now(std::span<const uint8_t> datagram);  ///< On the socket, counted.
  void take_datagram(std::span<const uint8_t> datagram, TimePoint now);
  void remember_send_time(uint32_t client_time_ms, TimePoint at);
  void set_state(ClientState state, std::string message);
  uint32_t client_time_ms(TimePoint now) const;

  ClientConfig config_;
  UdpSocket socket_;
  PacketWriter writer_;
  std::array<uint8_t, kMaxDatagramBytes> receive_buffer_{};
  Endpoint server_;
  Endpoint from_;  ///< Scratch for receive().

  // Connection.
  ClientState state_ = ClientState::kClosed;
  std::string status_ = "not started";
  uint64_t library_hash_ = 0;
  std::string name_;
  std::array<uint8_t, 64> cookie_{};
  size_t cookie_size_ = 0;  ///< 0: no Challenge yet.
  TimePoint started_at_{};
  TimePoint accepted_at_{};
  TimePoint last_heard_{};
  TimePoint next_handshake_send_{};
  AcceptInfo accept_;
  RefuseInfo refuse_;
  SceneDownload scene_download_;

  // Input.
  ControlInput held_;
  std::array<wire::InputCommand, kInputRedundancy> commands_{};  ///< Newest last.
  int num_commands_ = 0;
  uint32_t sequence_ = 0;
  uint32_t ack_input_ = 0;
  uint32_t payload_since_ = 0;  ///< Sequence of the first command holding the current input.
  TimePoint handshake_since_{};  ///< start(), the first challenge, or the server's latest "queued": the timeout runs from it.
  /// config_.handshake_timeout, or four round trips as the first challenge measured them if longer.
  std::chrono::milliseconds handshake_timeout_{5000};
  TimePoint last_input_sent_{};
  TimePoint last_packet_sent_{};

  // Snapshots.
  bool has_snapshot_ = false;
  uint32_t snapshot_tick_ = 0;
  uint32_t snapshot_server_ms_ = 0;
  int snapshot_parts_ = 0;
  std::bitset<256> snapshot_parts_seen_;
  std::vector<wire::AvatarState> avatars_;
  std::vector<wire::AvatarState> decoded_;  ///< Scratch: one part's avatars.
  AvatarHistory history_;                   ///< Snapshots held whole, for the packed avatars' references.
  uint32_t acked_snapshot_ = 0;             ///< The newest of them (sent in every Input).
  uint32_t ack_sent_ = 0;                   ///< acked_snapshot_ as last sent: an idle client sends it when it changes.
  std::vector<FighterPoseState> fighters_;
  std::vector<TerrainBodyState> terrain_bodies_;
  // The impairment layer (null when inactive): what we send waits in up_, what arrives in down_.
  std::unique_ptr<ImpairedQueue> up_, down_;
  // The session's keys (session_crypto.hpp): made at start(), used from the Accept on.
  SessionKeyPair key_pair_;
  Sealer sealer_;
  Opener opener_;
  PacketWriter seal_writer_;
  TimePoint now_{};  ///< The latest time given to start / poll / flush (what send() stamps).
  std::vector<StrikeEventInfo> new_strike_events_;
  uint32_t last_strike_sequence_ = 0;
  bool has_own_avatar_ = false;
  wire::AvatarState own_avatar_{};
  uint32_t own_avatar_tick_ = 0;
  TimePoint last_new_tick_at_{};
  uint32_t newest_echo_ms_ = 0;
  /// When the last few Inputs / Heartbeats left, by their client time: an echo then gives the
  /// exact round trip instead of one rounded to the millisecond.
  struct SentTime {
    uint32_t client_time_ms = 0;
    TimePoint at{};
  };
  std::array<SentTime, 64> sent_times_{};
  size_t next_sent_time_ = 0;

  // Measurements.
  LogHistogram rtt_ms_;
  LogHistogram snapshot_interval_ms_;
  double last_rtt_ms_ = 0;
  uint64_t bytes_received_ = 0, bytes_sent_ = 0, packets_received_ = 0;
  uint64_t inputs_sent_ = 0, send_failures_ = 0;
  uint64_t snapshot_packets_ = 0, snapshot_ticks_ = 0;
  DropCounters drops_;
  ServerFigures stats_;
  uint64_t stats_count_ = 0;
  TreeView tree_;  ///< Node arrays reserved for kMaxTreeSamples once.
  uint64_t tree_count_ = 0;
};

}  // namespace foresight::protocol

// ClientConnection against a scripted fake server on loopback, with an injected clock: the
// handshake, Inputs with redundancy, idle heartbeats, snapshot merging, round-trip times,
// refusals, timeouts and every kind of datagram the client must drop.
#include "support/alloc_counter.hpp"
#include "protocol/sent_views.hpp"
#include "transport/client_connection.hpp"
#include "transport/session_crypto.hpp"
#include "protocol/input_packet.hpp"

#include <gtest/gtest.h>

#include <poll.h>

#include <vector>

namespace foresight::protocol {
namespace {

using std::chrono::milliseconds;
using TimePoint = ClientConnection::TimePoint;

constexpr uint64_t kHash = 0x1122334455667788ull;

/// The server end: a socket that reads what the client sends and answers by hand.
class FakeServer {
 public:
  FakeServer() {
    std::string error;
    EXPECT_TRUE(socket_.open("127.0.0.1", 0, error)) << error;
    EXPECT_TRUE(parse_endpoint("127.0.0.1:" + std::to_string(socket_.local_port()), endpoint_, error));
  }
  const Endpoint& endpoint() const { return endpoint_; }

  /// The next datagram from the client (waits up to 1 s), or nullptr when none came; a Sealed
  /// one of the session is opened (its inner packet returned). A ConnectResponse gives the
  /// client's session key.
  const wire::Packet* receive() {
    if (!socket_.wait_readable(1000)) return nullptr;
    const ptrdiff_t n = socket_.receive(buffer_, client_);
    if (n < 0) return nullptr;
    last_ = {buffer_.data(), static_cast<size_t>(n)};
    DropReason reason = DropReason::kNone;
    const wire::Packet* p = packet_read(last_, reason);
    if (p == nullptr) return nullptr;
    if (const auto* r = p->message_as_ConnectResponse(); r && r->client_key())
      client_key_.assign(r->client_key()->begin(), r->client_key()->end());
    if (const auto* s = p->message_as_Sealed()) return opener_.open(*s, reason);
    return p;
  }
  /// The raw bytes of the last datagram received.
  std::span<const uint8_t> last_datagram() const { return last_; }
  /// The next datagram of type T, skipping others; nullptr when none came.
  template <typename T>
  const T* receive_a() {
    for (int i = 0; i < 64; ++i) {
      const wire::Packet* p = receive();
      if (p == nullptr) return nullptr;
      if (const T* m = p->message_as<T>()) return m;
    }
    return nullptr;
  }
  /// True when the client sent nothing (within 50 ms).
  bool silent() { return !socket_.wait_readable(50); }
  void drain() {
    while (socket_.wait_readable(20)) socket_.receive(buffer_, client_);
  }
  /// After the Accept, sealed as a real server does (what cannot be sealed goes as it is).
  void send(std::span<const uint8_t> bytes) {
    const auto sealed = sealer_.ready() ? sealer_.seal(seal_writer_, bytes) : std::span<const uint8_t>();
    send_raw(sealed.empty() ? bytes : sealed);
  }
  void send_raw(std::span<const uint8_t> bytes) {
    last_sent_.assign(bytes.begin(), bytes.end());
    socket_.send(bytes, client_);
  }
  /// The last datagram sent, as it went on the wire.
  const std::vector<uint8_t>& last_sent() const { return last_sent_; }
  PacketWriter& writer() { return writer_; }

  void send_challenge() {
    const uint8_t cookie[8] = {9, 8, 7, 6, 5, 4, 3, 2};
    auto& fbb = writer_.begin();
    send(writer_.finish(wire::CreateChallenge(fbb, fbb.CreateVector(cookie, 8))));
  }
  void send_accept(uint32_t session, uint32_t avatar) {
    SessionKeys keys;
    EXPECT_TRUE(session_keys_server(keys_, client_key_, keys)) << "no client key seen";
    auto& fbb = writer_.begin();
    const auto key = fbb.CreateVector(keys_.public_key.data(), keys_.public_key.size());
    send_raw(writer_.finish(wire::CreateAccept(fbb, session, avatar, fbb.CreateString("maze"),
                                               fbb.CreateString("default"), kHash, 60, 20, key)));
    sealer_.set(session, keys.send);
    opener_.set(session, keys.receive);
  }
  void send_snapshot(uint32_t tick, uint8_t part, uint8_t parts, std::vector<uint32_t> ids,
                     uint32_t ack_input = 0, uint32_t echo = 0) {
    std::vector<wire::AvatarState> avatars;
    for (uint32_t id : ids) avatars.emplace_back(id, 1000 * int32_t(id), -500, -1, 0, 0, 0, 0, 0);
    std::vector<uint8_t> packed;
    pack_avatars(avatars, packed);
    auto& fbb = writer_.begin();
    const auto bits = fbb.CreateVector(packed);
    send(writer_.finish(wire::CreateSnapshot(fbb, tick, part, parts, ack_input, echo, 0, 0, 0, 0,
                                             static_cast<uint16_t>(avatars.size()), bits)));
  }

 private:
  UdpSocket socket_;
  Endpoint endpoint_;
  Endpoint client_;
  PacketWriter writer_;
  std::array<uint8_t, 2048> buffer_{};
  std::span<const uint8_t> last_;
  std::vector<uint8_t> last_sent_;
  SessionKeyPair keys_ = session_keypair();
  std::vector<uint8_t> client_key_;
  Sealer sealer_;
  Opener opener_;
  PacketWriter seal_writer_;
};

/// Waits until the client's socket has something, then polls it at the injected time.
void deliver(ClientConnection& c, TimePoint now) {
  pollfd p{c.socket_fd(), POLLIN, 0};
  ::poll(&p, 1, 1000);
  c.poll(now);
}

class ClientConnectionTest : public ::testing::Test {
 protected:
  TimePoint at(int ms) const { return t0_ + milliseconds(ms); }

  /// start() and the whole handshake: the client is connected as session 5, avatar 3, at 100 ms.
  void connect() {
    ASSERT_TRUE(client_.start(server_.endpoint(), kHash, "bot-0", at(0)));
    ASSERT_NE(server_.receive_a<wire::ConnectRequest>(), nullptr);
    server_.send_challenge();
    deliver(client_, at(50));
    ASSERT_NE(server_.receive_a<wire::ConnectResponse>(), nullptr);
    server_.send_accept(5, 3);
    deliver(client_, at(100));
    ASSERT_EQ(client_.state(), ClientState::kConnected) << client_.status_message();
  }

  const TimePoint t0_ = ClientConnection::Clock::now();
  FakeServer server_;
  ClientConnection client_;
};

TEST_F(ClientConnectionTest, HandshakeResendsUntilAnsweredThenConnects) {
  ASSERT_TRUE(client_.start(server_.endpoint(), kHash, "bot-0", at(0)));
  EXPECT_EQ(client_.state(), ClientState::kConnecting);
  const auto* request = server_.receive_a<wire::ConnectRequest>();
  ASSERT_NE(request, nullptr);
  EXPECT_EQ(request->protocol(), kProtocolVersion);
  EXPECT_EQ(request->library_hash(), kHash);
  EXPECT_EQ(request->client_name()->str(), "bot-0");

  client_.flush(at(100));
  EXPECT_TRUE(server_.silent()) << "resent before 250 ms";
  client_.flush(at(260));
  EXPECT_NE(server_.receive_a<wire::ConnectRequest>(), nullptr) << "not resent after 250 ms";

  server_.send_challenge();
  deliver(client_, at(300));
  const auto* response = server_.receive_a<wire::ConnectResponse>();
  ASSERT_NE(response, nullptr) << "the challenge is answered at once";
  ASSERT_EQ(response->cookie()->size(), 8u);
  EXPECT_EQ(response->cookie()->Get(0), 9);
  EXPECT_EQ(response->library_hash(), kHash);
  client_.flush(at(560));
  EXPECT_NE(server_.receive_a<wire::ConnectResponse>(), nullptr) << "response resent";

  server_.send_accept(5, 3);
  deliver(client_, at(600));
  ASSERT_EQ(client_.state(), ClientState::kConnected);
  EXPECT_EQ(client_.accept().session, 5u);
  EXPECT_EQ(client_.accept().avatar, 3u);
  EXPECT_EQ(client_.accept().scene, "maze");
  EXPECT_EQ(client_.accept().snapshot_hz, 20);
  EXPECT_NE(client_.status_message().find("session 5"), std::string::npos);

  server_.send_accept(5, 3);  // answer to a resent response: harmless
  deliver(client_, at(610));
  EXPECT_EQ(client_.state(), ClientState::kConnected);
  EXPECT_EQ(client_.drops().total(), 0u);
}

TEST_F(ClientConnectionTest, InputsRepeatTheLastCommandsNewestLast) {
  connect();
  ControlInput forward;
  forward.camera_dir = vec2(0.0f, 1.0f);
  forward.camera_yaw_rad = 1.0f;
  client_.set_input(forward);
  const wire::Input* input = nullptr;
  for (int frame = 1; frame <= 10; ++frame) {
    client_.flush(at(100 + 33 * frame));
    input = server_.receive_a<wire::Input>();
    ASSERT_NE(input, nullptr) << "frame " << frame;
    EXPECT_EQ(input->session(), 5u);
    const size_t expected = std::min(frame, kInputRedundancy);
    ASSERT_EQ(input->commands()->size(), expected);
    EXPECT_EQ(input->commands()->Get(static_cast<uint32_t>(expected - 1))->sequence(),
              static_cast<uint32_t>(frame));
    EXPECT_EQ(input->commands()->Get(0)->sequence(), static_cast<uint32_t>(frame - expected + 1));
  }
  const ControlInput decoded = control_input_from_command(*input->commands()->Get(7));
  EXPECT_NEAR(decoded.camera_dir.y, 1.0f, 1e-6f);
  EXPECT_NEAR(decoded.camera_yaw_rad, 1.0f, 1e-4f);
  EXPECT_EQ(client_.inputs_sent(), 10u);
  EXPECT_EQ(client_.input_sequence(), 10u);

  // ack_snapshot follows the newest snapshot tick.
  server_.send_snapshot(77, 0, 1, {3});
  deliver(client_, at(500));
  client_.flush(at(510));
  input = server_.receive_a<wire::Input>();
  ASSERT_NE(input, nullptr);
  EXPECT_EQ(input->ack_snapshot(), 77u);
}

TEST_F(ClientConnectionTest, IdleClientSendsOnlyAcknowledgementsAndHeartbeats) {
  connect();
  client_.set_input(ControlInput{});  // stop
  client_.flush(at(133));
  ASSERT_NE(server_.receive_a<wire::Input>(), nullptr) << "the first stop is sent";
  client_.flush(at(166));
  ASSERT_NE(server_.receive_a<wire::Input>(), nullptr) << "not idle until the server acks";
  server_.send_snapshot(1, 0, 1, {3}, /*ack_input=*/2);
  deliver(client_, at(180));
  server_.drain();
  client_.flush(at(200));
  // Idle, but a new snapshot held whole is acknowledged (the server codes the next ones against
  // it): an Input without commands.
  const auto* ack = server_.receive_a<wire::Input>();
  ASSERT_NE(ack, nullptr);
  EXPECT_EQ(ack->ack_snapshot(), 1u);
  EXPECT_TRUE(ack->commands() == nullptr || ack->commands()->size() == 0);
  server_.drain();
  client_.flush(at(900));
  EXPECT_TRUE(server_.silent()) << "idle: nothing new to say";
  server_.send_snapshot(1, 0, 1, {3}, 2);  // a repeat: keeps the server "heard from", nothing to acknowledge
  deliver(client_, at(1000));
  client_.flush(at(1210));
  const auto* hb = server_.receive_a<wire::Heartbeat>();
  ASSERT_NE(hb, nullptr) << "a heartbeat once a second while idle";
  EXPECT_EQ(hb->session(), 5u);
  server_.drain();
  server_.send_snapshot(2, 0, 1, {3}, 2);
  deliver(client_, at(1300));
  client_.flush(at(1310));
  const auto* ack2 = server_.receive_a<wire::Input>();
  ASSERT_NE(ack2, nullptr);
  EXPECT_EQ(ack2->ack_snapshot(), 2u);
  server_.drain();

  ControlInput left;
  left.camera_dir = vec2(-1.0f, 0.0f);
  client_.set_input(left);
  client_.flush(at(1400));
  const auto* input = server_.receive_a<wire::Input>();
  ASSERT_NE(input, nullptr) << "a new input ends the idle time";
  EXPECT_EQ(input->commands()->Get(input->commands()->size() - 1)->sequence(), 3u);
}

TEST_F(ClientConnectionTest, SnapshotPartsMergeAndANewerTickReplaces) {
  connect();
  server_.send_snapshot(10, 0, 2, {1, 2});
  deliver(client_, at(200));
  EXPECT_TRUE(client_.has_snapshot());
  EXPECT_EQ(client_.snapshot_tick(), 10u);
  EXPECT_EQ(client_.avatars().size(), 2u);
  EXPECT_EQ(client_.own_avatar(), nullptr);
  EXPECT_EQ(client_.acked_snapshot(), 0u) << "only a snapshot held whole is acknowledged";

  server_.send_snapshot(10, 1, 2, {3});
  server_.send_snapshot(10, 1, 2, {3});  // duplicated datagram
  server_.send_snapshot(9, 0, 1, {1});   // late older tick
  deliver(client_, at(210));
  EXPECT_EQ(client_.snapshot_tick(), 10u);
  EXPECT_EQ(client_.snapshot_parts(), 2);
  EXPECT_EQ(client_.snapshot_parts_received(), 2);
  ASSERT_EQ(client_.avatars().size(), 3u);
  ASSERT_NE(client_.own_avatar(), nullptr);
  EXPECT_EQ(client_.own_avatar()->id(), 3u);
  EXPECT_EQ(client_.own_avatar()->start_x_mm(), 3000);
  EXPECT_EQ(client_.own_avatar_tick(), 10u);
  EXPECT_EQ(client_.acked_snapshot(), 10u);

  server_.send_snapshot(13, 1, 2, {4, 5});
  deliver(client_, at(260));
  EXPECT_EQ(client_.snapshot_tick(), 13u);
  EXPECT_EQ(client_.acked_snapshot(), 10u) << "13 is not whole yet";
  EXPECT_EQ(client_.avatars().size(), 2u);
  EXPECT_EQ(client_.snapshot_parts_received(), 1);
  ASSERT_NE(client_.own_avatar(), nullptr) << "the last seen own state is kept";
  EXPECT_EQ(client_.own_avatar_tick(), 10u);
  EXPECT_EQ(client_.snapshot_ticks(), 2u);
  EXPECT_EQ(client_.snapshot_interval_ms().count(), 1u);
  EXPECT_NEAR(client_.snapshot_interval_ms().max(), 60.0, 1e-9);
  EXPECT_EQ(client_.drops().total(), 0u);
}

TEST_F(ClientConnectionTest, AvatarsCodedAgainstASnapshotItDoesNotHoldAreDroppedAndCounted) {
  connect();
  // The server codes snapshot 21 against snapshot 20, which never reached this client.
  WholeViewSender server_side;
  server_side.remember(20, 30, std::vector<wire::AvatarState>{wire::AvatarState(1, 0, 0, -1, 2, 0, 3, 0, 0)});
  server_side.acknowledge(20);
  const std::vector<wire::AvatarState> now{wire::AvatarState(1, 0, 0, -1, 2, 0, 5, 0, 0)};
  AvatarDeltaEncoder encoder;
  server_side.plan(encoder, now, 21, 32);
  std::vector<uint8_t> packed;
  encoder.write_part(0, now.size(), packed);
  auto& fbb = server_.writer().begin();
  const auto bits = fbb.CreateVector(packed);
  server_.send(server_.writer().finish(wire::CreateSnapshot(fbb, 21, 0, 1, 0, 0, 0, 0, 0, 0, 1, bits)));
  deliver(client_, at(200));
  EXPECT_EQ(client_.drops().by_reason[size_t(DropReason::kMissingBaseline)], 1u);
  EXPECT_FALSE(client_.has_snapshot());
  EXPECT_EQ(client_.acked_snapshot(), 0u) << "it keeps acknowledging what it holds";
  // Whole states (what the server sends once its references age out) are taken again.
  server_.send_snapshot(22, 0, 1, {1});
  deliver(client_, at(250));
  EXPECT_EQ(client_.acked_snapshot(), 22u);
}

TEST_F(ClientConnectionTest, RoundTripIsMeasuredFromTheEcho) {
  connect();
  client_.flush(at(1000));
  const auto* input = server_.receive_a<wire::Input>();
  ASSERT_NE(input, nullptr);
  const uint32_t sent_ms = input->client_time_ms();
  EXPECT_NE(sent_ms, 0u);
  server_.send_snapshot(1, 0, 1, {3}, 0, sent_ms);
  deliver(client_, at(1040));
  ASSERT_EQ(client_.rtt_ms().count(), 1u);
  EXPECT_NEAR(client_.last_rtt_ms(), 40.0, 1e-9);
  server_.send_snapshot(2, 0, 1, {3}, 0, sent_ms);  // the same echo again: no new sample
  deliver(client_, at(1090));
  EXPECT_EQ(client_.rtt_ms().count(), 1u);
}

TEST_F(ClientConnectionTest, RefusalIsFinalAndExplained) {
  ASSERT_TRUE(client_.start(server_.endpoint(), kHash, "bot-0", at(0)));
  ASSERT_NE(server_.receive_a<wire::ConnectRequest>(), nullptr);
  auto& w = server_.writer();
  auto& fbb = w.begin();
  server_.send(w.finish(wire::CreateRefuse(fbb, wire::RefuseReason::Library,
                                           fbb.CreateString("motion library differs"), 0xabcdefull)));
  deliver(client_, at(30));
  EXPECT_EQ(client_.state(), ClientState::kRefused);
  EXPECT_EQ(client_.refuse().reason, wire::RefuseReason::Library);
  EXPECT_EQ(client_.refuse().server_library_hash, 0xabcdefull);
  const std::string& why = client_.status_message();
  EXPECT_NE(why.find("motion library differs"), std::string::npos) << why;
  EXPECT_NE(why.find("1122334455667788"), std::string::npos) << why;
  EXPECT_NE(why.find("0000000000abcdef"), std::string::npos) << why;
  server_.drain();
  client_.flush(at(1000));
  EXPECT_TRUE(server_.silent()) << "a refused client stops sending";
}

TEST_F(ClientConnectionTest, HandshakeTimesOutAfterFiveSeconds) {
  ASSERT_TRUE(client_.start(server_.endpoint(), kHash, "bot-0", at(0)));
  client_.update(at(4999));
  EXPECT_EQ(client_.state(), ClientState::kConnecting);
  client_.update(at(5000));
  EXPECT_EQ(client_.state(), ClientState::kTimedOut);
  EXPECT_NE(client_.status_message().find("no answer"), std::string::npos);
}

TEST_F(ClientConnectionTest, SilentServerIsGoneAfterFiveSeconds) {
  connect();
  client_.update(at(5099));
  EXPECT_EQ(client_.state(), ClientState::kConnected);
  client_.update(at(5100));
  EXPECT_EQ(client_.state(), ClientState::kServerGone);
}

// Copies of the Accept travel in the clear: once connected they are not taken as hearing from
// the server, or anyone sending them from its address (the session id is guessable) would keep
// the client from noticing that its server is gone.
TEST_F(ClientConnectionTest, AcceptsInTheClearDoNotKeepAGoneServerAlive) {
  connect();
  for (int ms = 500; ms <= 6000; ms += 500) {
    server_.send_accept(5, 3);
    deliver(client_, at(ms));
    client_.update(at(ms));
  }
  EXPECT_EQ(client_.state(), ClientState::kServerGone);
}

TEST_F(ClientConnectionTest, UnsealedOrForgedServerMessagesAreDroppedOnceConnected) {
  connect();
  // A snapshot not sealed with the session's key: anyone on the way could have sent it.
  const wire::AvatarState avatar(7, 0, 0, -1, 0, 0, 0, 0, 0);
  std::vector<uint8_t> packed;
  pack_avatars({&avatar, 1}, packed);
  auto& fbb = server_.writer().begin();
  server_.send_raw(server_.writer().finish(
      wire::CreateSnapshot(fbb, 50, 0, 1, 0, 0, 0, 0, 0, 0, 1, fbb.CreateVector(packed))));
  deliver(client_, at(200));
  EXPECT_EQ(client_.drops().by_reason[size_t(DropReason::kUnauthenticated)], 1u);
  EXPECT_FALSE(client_.has_snapshot());
  // A Sealed message with a made-up payload: forged.
  auto& fbb2 = server_.writer().begin();
  const std::vector<uint8_t> junk(80, 7);
  server_.send_raw(server_.writer().finish(wire::CreateSealed(fbb2, 5, 1, fbb2.CreateVector(junk))));
  deliver(client_, at(210));
  EXPECT_EQ(client_.drops().by_reason[size_t(DropReason::kUnauthenticated)], 2u);
  // The genuine, sealed one counts, and a copy of it is a replay.
  server_.send_snapshot(51, 0, 1, {7});
  deliver(client_, at(220));
  EXPECT_TRUE(client_.has_snapshot());
  EXPECT_EQ(client_.snapshot_tick(), 51u);
  server_.send_raw(server_.last_sent());
  deliver(client_, at(230));
  EXPECT_EQ(client_.drops().by_reason[size_t(DropReason::kReplayed)], 1u);
}

TEST_F(ClientConnectionTest, ServerCanEndTheSession) {
  connect();
  PacketWriter w;
  server_.send(write_disconnect(w, 5));
  deliver(client_, at(200));
  EXPECT_EQ(client_.state(), ClientState::kServerGone);
}

TEST_F(ClientConnectionTest, BadDatagramsAreDroppedByReason) {
  connect();
  const uint8_t garbage[40] = {1, 2, 3};
  server_.send(garbage);
  deliver(client_, at(200));
  EXPECT_EQ(client_.drops().by_reason[size_t(DropReason::kBadIdentifier)], 1u);

  std::vector<uint8_t> huge(1500, 0);
  server_.send_raw(huge);
  deliver(client_, at(210));
  EXPECT_EQ(client_.drops().by_reason[size_t(DropReason::kTooLarge)], 1u);

  server_.send_challenge();  // not expected once connected
  deliver(client_, at(220));
  EXPECT_EQ(client_.drops().by_reason[size_t(DropReason::kUnexpected)], 1u);

  server_.send_snapshot(5, 2, 2, {1});  // part out of range
  deliver(client_, at(230));
  EXPECT_EQ(client_.drops().by_reason[size_t(DropReason::kInvalidInput)], 1u);
  EXPECT_FALSE(client_.has_snapshot());

  // A stranger who learned the port: dropped whatever it sends.
  UdpSocket stranger;
  std::string error;
  ASSERT_TRUE(stranger.open("127.0.0.1", 0, error));
  Endpoint client_endpoint;
  ASSERT_TRUE(parse_endpoint("127.0.0.1:" + std::to_string(client_.local_port()), client_endpoint, error));
  PacketWriter w;
  stranger.send(write_disconnect(w, 5), client_endpoint);
  deliver(client_, at(240));
  EXPECT_EQ(client_.drops().by_reason[size_t(DropReason::kUnexpected)], 2u);
  EXPECT_EQ(client_.state(), ClientState::kConnected);
  EXPECT_EQ(client_.drops().total(), 5u);
}

TEST_F(ClientConnectionTest, StatsAndDisconnect) {
  connect();
  client_.request_stats();
  const auto* request = server_.receive_a<wire::StatsRequest>();
  ASSERT_NE(request, nullptr);
  EXPECT_EQ(request->session(), 5u);
  auto& w = server_.writer();
  auto& fbb = w.begin();
  wire::ServerStatsBuilder b(fbb);
  b.add_tick(900);
  b.add_tick_ms_p99(3.5f);
  b.add_overruns(2);
  b.add_tree_size_mean(123.0f);
  server_.send(w.finish(b.Finish()));
  deliver(client_, at(200));
  ASSERT_EQ(client_.server_stats_count(), 1u);
  EXPECT_EQ(client_.server_stats().tick, 900u);
  EXPECT_FLOAT_EQ(client_.server_stats().tick_ms_p99, 3.5f);
  EXPECT_EQ(client_.server_stats().overruns, 2u);
  EXPECT_FLOAT_EQ(client_.server_stats().tree_size_mean, 123.0f);

  client_.disconnect();
  EXPECT_EQ(client_.state(), ClientState::kClosed);
  int disconnects = 0;
  while (const auto* d = server_.receive_a<wire::Disconnect>()) {
    EXPECT_EQ(d->session(), 5u);
    ++disconnects;
  }
  EXPECT_EQ(disconnects, 3);
}

TEST_F(ClientConnectionTest, TreeSummariesAreCopiedAndBadOnesDropped) {
  connect();
  client_.request_tree();
  const auto* request = server_.receive_a<wire::TreeRequest>();
  ASSERT_NE(request, nullptr);
  EXPECT_EQ(request->session(), 5u);
  auto send_tree = [&](std::vector<wire::TreeNodeSample> nodes) {
    auto& w = server_.writer();
    auto& fbb = w.begin();
    const auto sampled = fbb.CreateVectorOfStructs(nodes.data(), nodes.size());
    server_.send(w.finish(wire::CreateTreeSummary(fbb, 77, 3, 500, 1500, 2000, 1000, 2000, sampled)));
  };
  // Root ends 50 cm ahead of the origin; a chosen child and an ordinary one below it.
  send_tree({wire::TreeNodeSample(0, 50, kTreeNoParent, 0, 0, 0, 0), wire::TreeNodeSample(50, 100, 0, 1, kTreeNodeChosen, 12, 16384),
             wire::TreeNodeSample(-50, 100, 0, 1, 0, 0, 0)});
  deliver(client_, at(200));
  ASSERT_EQ(client_.tree_count(), 1u);
  const TreeView& t = client_.tree();
  EXPECT_EQ(t.tick, 77u);
  EXPECT_EQ(t.avatar, 3u);
  EXPECT_EQ(t.nodes, 500u);
  ASSERT_EQ(t.size(), 3u);
  EXPECT_NEAR(t.origin_m.x, 1.0f, 1e-6f);
  EXPECT_NEAR(t.end_m[0].y, 2.5f, 1e-5f);
  EXPECT_NEAR(t.end_m[1].x, 1.5f, 1e-5f);
  EXPECT_NEAR(t.chosen_child_end_m.x, 1.5f, 1e-6f);
  EXPECT_EQ(t.parent[0], kTreeNoParent);
  EXPECT_EQ(t.parent[2], 0u);
  EXPECT_EQ(t.chosen[1], 1u);
  EXPECT_EQ(t.chosen[2], 0u);
  // Segment and start heading (a quarter turn) for ghost poses; node 1 starts at the root's end.
  EXPECT_EQ(t.segment[1], 12u);
  EXPECT_NEAR(t.start_heading_rad[1], 0.5f * kPi, 1e-4f);
  EXPECT_NEAR(t.start(1).pos_m.y, t.end_m[0].y, 1e-6f);
  EXPECT_NEAR(t.start(0).pos_m.x, t.origin_m.x, 1e-6f);
  // A parent that does not come before its node: dropped, the previous summary kept.
  const uint64_t invalid = client_.drops().by_reason[static_cast<size_t>(DropReason::kInvalidInput)];
  send_tree({wire::TreeNodeSample(0, 0, kTreeNoParent, 0, 0, 0, 0), wire::TreeNodeSample(0, 0, 1, 1, 0, 0, 0)});
  deliver(client_, at(250));
  EXPECT_EQ(client_.tree_count(), 1u);
  EXPECT_EQ(client_.tree().size(), 3u);
  EXPECT_EQ(client_.drops().by_reason[static_cast<size_t>(DropReason::kInvalidInput)], invalid + 1);
  // A full-size summary: copied into the reserved arrays without allocating.
  std::vector<wire::TreeNodeSample> full(kMaxTreeSamples, wire::TreeNodeSample(1, 1, 0, 1, 0, 0, 0));
  full[0] = wire::TreeNodeSample(0, 0, kTreeNoParent, 0, 0, 0, 0);
  send_tree(full);
  pollfd p{client_.socket_fd(), POLLIN, 0};
  ::poll(&p, 1, 1000);
  {
    test::AllocationCount counting;
    client_.poll(at(300));
    EXPECT_EQ(counting.allocations(), 0);
  }
  EXPECT_EQ(client_.tree_count(), 2u);
  EXPECT_EQ(client_.tree().size(), kMaxTreeSamples);
}

TEST(AllocationCount, SeesAnAllocation) {
  test::AllocationCount counting;
  std::vector<int> v(static_cast<size_t>(counting.allocations() + 100));
  EXPECT_GE(counting.allocations(), 1) << v.size();
}

TEST_F(ClientConnectionTest, AWarmConnectionAllocatesNothingPerPacket) {
  connect();
  ControlInput input;
  input.camera_dir = vec2(0.0f, 1.0f);
  int allocations = 0;
  auto frame = [&](int i, bool count) {
    server_.send_snapshot(static_cast<uint32_t>(10 + i), 0, 2, {1, 2, 3}, static_cast<uint32_t>(i), 0);
    server_.send_snapshot(static_cast<uint32_t>(10 + i), 1, 2, {4, 5});
    pollfd p{client_.socket_fd(), POLLIN, 0};
    ::poll(&p, 1, 1000);
    input.camera_yaw_rad = 0.01f * static_cast<float>(i);
    test::AllocationCount counting(count);
    client_.set_input(input);
    client_.update(at(200 + 33 * i));
    if (count) allocations += counting.allocations();
    server_.drain();
  };
  for (int i = 0; i < 5; ++i) frame(i, false);  // warm up
  for (int i = 5; i < 50; ++i) frame(i, true);
  EXPECT_EQ(allocations, 0);
  EXPECT_EQ(client_.snapshot_ticks(), 50u);
  EXPECT_EQ(client_.inputs_sent(), 50u);
}

}  // namespace
}  // namespace foresight::protocol

#pragma once
// A bare client for server tests: a real UDP socket on loopback that sends hand-built packets
// (valid and hostile) and reads the server's replies, with the server ticked in between.
#include "protocol/avatar_delta.hpp"
#include "protocol/input_packet.hpp"
#include "protocol/packet.hpp"
#include "protocol/quantize.hpp"
#include "transport/session_crypto.hpp"
#include "transport/udp_socket.hpp"
#include "server.hpp"

#include <gtest/gtest.h>

#include <optional>
#include <vector>

namespace foresight::test {

/// A snapshot part's avatars as a client that acknowledges nothing reads them (RawClient sends
/// ack 0, so the server codes every avatar whole); a part that does not decode fails the test.
inline std::vector<wire::AvatarState> snapshot_avatars(const wire::Snapshot& s) {
  std::vector<wire::AvatarState> out;
  EXPECT_EQ(protocol::snapshot_avatars(s, protocol::AvatarHistory{}, out), protocol::AvatarDecodeStatus::kOk);
  return out;
}

class RawClient {
 public:
  explicit RawClient(uint16_t server_port) {
    std::string error;
    EXPECT_TRUE(socket_.open("127.0.0.1", 0, error)) << error;
    server_ = protocol::Endpoint(asio::ip::make_address("127.0.0.1"), server_port);
  }
  void send(std::span<const uint8_t> bytes) { socket_.send(bytes, server_); }
  void send_raw(const std::vector<uint8_t>& bytes) { socket_.send(bytes, server_); }
  /// A session message (a whole packet), sealed with this session's key as the protocol wants.
  void send_session(std::span<const uint8_t> inner) { send(sealer_.seal(seal_writer_, inner)); }
  /// The same, kept instead of sent (to replay or tamper with it).
  std::vector<uint8_t> seal(std::span<const uint8_t> inner) {
    const auto bytes = sealer_.seal(seal_writer_, inner);
    return {bytes.begin(), bytes.end()};
  }

  /// Every datagram waiting (copied, so packets stay valid); our session's Sealed ones opened (the
  /// inner packet's bytes in their place; one that does not open is kept as it came).
  std::vector<std::vector<uint8_t>> receive_all() {
    std::vector<std::vector<uint8_t>> out = receive_raw();
    for (std::vector<uint8_t>& d : out) {
      protocol::DropReason reason;
      const wire::Packet* p = protocol::packet_read(d, reason);
      const wire::Sealed* sealed = p ? p->message_as_Sealed() : nullptr;
      if (sealed != nullptr && opener_.ready() && opener_.open(*sealed, reason) != nullptr)
        d.assign(opener_.plain().begin(), opener_.plain().end());
    }
    return out;
  }
  /// Every datagram waiting, as it came off the wire.
  std::vector<std::vector<uint8_t>> receive_raw() {
    std::vector<std::vector<uint8_t>> out;
    std::vector<uint8_t> buffer(protocol::kMaxDatagramBytes + 1);
    protocol::Endpoint from;
    for (;;) {
      const ptrdiff_t n = socket_.receive(buffer, from);
      if (n < 0) break;
      out.emplace_back(buffer.begin(), buffer.begin() + n);
    }
    return out;
  }
  /// The first waiting message of type `type`, as a copy of its datagram.
  std::optional<std::vector<uint8_t>> receive(wire::Message type) {
    for (auto& d : receive_all()) {
      protocol::DropReason reason;
      const wire::Packet* p = protocol::packet_read(d, reason);
      if (p != nullptr && p->message_type() == type) return d;
    }
    return std::nullopt;
  }

  /// Runs the handshake against `server` (ticked at `now`, advancing 1 ms per tick); returns the
  /// Accept's session and avatar, or the refusal's bytes via `refuse`.
  bool connect(server::Server& s, server::Clock::time_point& now, uint64_t library_hash,
               std::vector<uint8_t>* refuse = nullptr, std::string_view name = "test") {
    send(protocol::write_connect_request(writer_, library_hash, name));
    std::optional<std::vector<uint8_t>> challenge;
    for (int i = 0; i < 50 && !challenge; ++i) {
      s.run_tick(now += std::chrono::milliseconds(1));
      challenge = receive(wire::Message::Challenge);
    }
    if (!challenge) return false;
    protocol::DropReason reason;
    const auto* cookie = protocol::packet_read(*challenge, reason)->message_as_Challenge()->cookie();
    send(protocol::write_connect_response(writer_, library_hash, {cookie->data(), cookie->size()}, name,
                                          keys_.public_key));
    for (int i = 0; i < 50; ++i) {
      s.run_tick(now += std::chrono::milliseconds(1));
      for (auto& d : receive_all()) {
        const wire::Packet* p = protocol::packet_read(d, reason);
        if (p == nullptr) continue;
        if (const auto* a = p->message_as_Accept()) {
          session = a->session();
          avatar = a->avatar();
          protocol::SessionKeys k;
          const auto* server_key = a->server_key();
          if (server_key == nullptr || !protocol::session_keys_client(keys_, {server_key->data(), server_key->size()}, k))
            return false;
          sealer_.set(session, k.send);
          opener_.set(session, k.receive);
          return true;
        }
        if (p->message_as_Refuse() != nullptr) {
          if (refuse != nullptr) *refuse = d;
          return false;
        }
      }
    }
    return false;
  }

  /// An Input holding one command: camera-space direction `dir` seen from a camera with yaw `yaw_rad`.
  void send_input(vec2 dir, uint32_t sequence, float yaw_rad = 0.0f, bool crouch = false) {
    ControlInput in;
    in.camera_dir = dir;
    in.camera_yaw_rad = yaw_rad;
    in.crouch = crouch;
    const wire::InputCommand cmd = protocol::input_command_from(in, sequence);
    send_session(protocol::write_input(writer_, session, 0, sequence, {&cmd, 1}));
  }

  uint32_t session = 0;
  uint32_t avatar = 0;
  protocol::PacketWriter writer_;

 private:
  protocol::SessionKeyPair keys_ = protocol::session_keypair();
  protocol::Sealer sealer_;
  protocol::Opener opener_;
  protocol::PacketWriter seal_writer_;
  protocol::UdpSocket socket_;
  protocol::Endpoint server_;
};

/// A server on a free loopback port, deterministic growth (expansions per tick).
inline server::ServerConfig test_server_config(const std::string& scene) {
  server::ServerConfig c;
  c.scene = scene;
  c.bind_address = "127.0.0.1";
  c.port = 0;
  c.expansions_per_avatar = 200;
  c.threads = 1;
  c.status_every_s = 0;
  c.fighters = 0;  // the scene's NPC fighters only where a test asks for them
  c.admin_port = -1;  // the admin endpoint only where a test asks for it (admin_test.cpp)
  return c;
}

}  // namespace foresight::test

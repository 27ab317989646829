#include "protocol/packet.hpp"

#include <numeric>

namespace foresight::protocol {

const char* drop_reason_name(DropReason reason) {
  switch (reason) {
    case DropReason::kNone: return "none";
    case DropReason::kTooSmall: return "too_small";
    case DropReason::kTooLarge: return "too_large";
    case DropReason::kBadIdentifier: return "bad_identifier";
    case DropReason::kMalformed: return "malformed";
    case DropReason::kEmpty: return "empty";
    case DropReason::kUnexpected: return "unexpected";
    case DropReason::kRateLimited: return "rate_limited";
    case DropReason::kInvalidInput: return "invalid_input";
    case DropReason::kUnauthenticated: return "unauthenticated";
    case DropReason::kReplayed: return "replayed";
    case DropReason::kMissingBaseline: return "missing_baseline";
    case DropReason::kCount: break;
  }
  return "unknown";
}

uint64_t DropCounters::total() const {
  return std::accumulate(by_reason.begin(), by_reason.end(), uint64_t{0});
}

const wire::Packet* packet_read(std::span<const uint8_t> datagram, DropReason& reason) {
  // Root offset + file identifier.
  if (datagram.size() < sizeof(flatbuffers::uoffset_t) + flatbuffers::kFileIdentifierLength) {
    reason = DropReason::kTooSmall;
    return nullptr;
  }
  if (datagram.size() > kMaxDatagramBytes) {
    reason = DropReason::kTooLarge;
    return nullptr;
  }
  if (!wire::PacketBufferHasIdentifier(datagram.data())) {
    reason = DropReason::kBadIdentifier;
    return nullptr;
  }
  flatbuffers::Verifier::Options options;
  options.max_depth = kVerifierMaxDepth;
  options.max_tables = kVerifierMaxTables;
  flatbuffers::Verifier verifier(datagram.data(), datagram.size(), options);
  if (!wire::VerifyPacketBuffer(verifier)) {
    reason = DropReason::kMalformed;
    return nullptr;
  }
  const wire::Packet* packet = wire::GetPacket(datagram.data());
  if (packet->message_type() == wire::Message::NONE || packet->message() == nullptr) {
    reason = DropReason::kEmpty;
    return nullptr;
  }
  reason = DropReason::kNone;
  return packet;
}

std::span<const uint8_t> write_connect_request(PacketWriter& w, uint64_t library_hash,
                                               std::string_view client_name) {
  auto& fbb = w.begin();
  const auto name = fbb.CreateString(client_name.substr(0, 64));
  // Pad so the request is never smaller than the Challenge it asks for (anti-amplification).
  static constexpr std::array<uint8_t, kMinConnectRequestBytes> kZeros{};
  const auto padding = fbb.CreateVector(kZeros.data(), kZeros.size());
  return w.finish(wire::CreateConnectRequest(fbb, kProtocolVersion, library_hash, name, padding));
}

std::span<const uint8_t> write_connect_response(PacketWriter& w, uint64_t library_hash,
                                                std::span<const uint8_t> cookie,
                                                std::string_view client_name, std::span<const uint8_t> client_key) {
  auto& fbb = w.begin();
  const auto c = fbb.CreateVector(cookie.data(), cookie.size());
  const auto name = fbb.CreateString(client_name.substr(0, 64));
  const auto key = client_key.empty() ? 0 : fbb.CreateVector(client_key.data(), client_key.size());
  return w.finish(wire::CreateConnectResponse(fbb, kProtocolVersion, library_hash, c, name, key));
}

std::span<const uint8_t> write_heartbeat(PacketWriter& w, uint32_t session, uint32_t client_time_ms) {
  auto& fbb = w.begin();
  return w.finish(wire::CreateHeartbeat(fbb, session, client_time_ms));
}

std::span<const uint8_t> write_disconnect(PacketWriter& w, uint32_t session) {
  auto& fbb = w.begin();
  return w.finish(wire::CreateDisconnect(fbb, session));
}

std::span<const uint8_t> write_stats_request(PacketWriter& w, uint32_t session) {
  auto& fbb = w.begin();
  return w.finish(wire::CreateStatsRequest(fbb, session));
}

std::span<const uint8_t> write_tree_request(PacketWriter& w, uint32_t session) {
  auto& fbb = w.begin();
  return w.finish(wire::CreateTreeRequest(fbb, session));
}

std::span<const uint8_t> write_scene_request(PacketWriter& w, uint32_t session, uint32_t offset) {
  auto& fbb = w.begin();
  return w.finish(wire::CreateSceneRequest(fbb, session, offset));
}

}  // namespace foresight::protocol

#pragma once
// Reading and writing datagrams. Every received buffer goes through packet_read(), which runs
// the FlatBuffers Verifier with size and depth limits before anything is read: a buffer that
// fails is dropped (and counted by the caller by reason), never trusted.
//
// Writing: PacketWriter owns one FlatBufferBuilder that is cleared and reused, so building a
// packet allocates nothing once the builder has grown to the largest packet.
#include "foresight_generated.h"
#include "protocol/protocol.hpp"

#include <flatbuffers/flatbuffers.h>

#include <array>
#include <cstdint>
#include <span>
#include <string_view>

namespace foresight::protocol {

enum class DropReason : uint8_t {
  kNone = 0,
  kTooSmall,       ///< Shorter than a FlatBuffer header.
  kTooLarge,       ///< Over kMaxDatagramBytes.
  kBadIdentifier,  ///< Not a Foresight packet (file identifier).
  kMalformed,      ///< Failed the Verifier.
  kEmpty,          ///< Verified, but holds no message.
  kUnexpected,     ///< A message this side never receives, or from someone not in session.
  kRateLimited,
  kInvalidInput,   ///< Out-of-range values (direction longer than 1, ...).
  kUnauthenticated,  ///< A session message not sealed, or sealed with the wrong key (forged).
  kReplayed,       ///< A sealed message whose sequence was seen (or is too old for the window).
  kMissingBaseline,  ///< Packed avatars refer to a snapshot this side does not hold (avatar_delta.hpp).
  kCount
};
const char* drop_reason_name(DropReason reason);

/// The verified packet, or nullptr with `reason` set.
const wire::Packet* packet_read(std::span<const uint8_t> datagram, DropReason& reason);

/// Per-reason drop counters.
struct DropCounters {
  std::array<uint64_t, static_cast<size_t>(DropReason::kCount)> by_reason{};
  void add(DropReason r) { ++by_reason[static_cast<size_t>(r)]; }
  uint64_t total() const;
};

class PacketWriter {
 public:
  PacketWriter() : fbb_(kMaxDatagramBytes) {}
  /// Start a packet: clears the builder.
  flatbuffers::FlatBufferBuilder& begin() {
    fbb_.Clear();
    return fbb_;
  }
  /// Finishes the packet holding `message` and returns its bytes (valid until the next begin()).
  template <typename T>
  std::span<const uint8_t> finish(flatbuffers::Offset<T> message) {
    const auto packet = wire::CreatePacket(fbb_, wire::MessageTraits<T>::enum_value, message.Union());
    wire::FinishPacketBuffer(fbb_, packet);
    return {fbb_.GetBufferPointer(), fbb_.GetSize()};
  }

 private:
  flatbuffers::FlatBufferBuilder fbb_;
};

/// Builders for the small control messages (the server's snapshot and stats builders live with
/// the server, the client's Input with the client side: they need their own state).
std::span<const uint8_t> write_connect_request(PacketWriter& w, uint64_t library_hash,
                                               std::string_view client_name);
std::span<const uint8_t> write_connect_response(PacketWriter& w, uint64_t library_hash,
                                                std::span<const uint8_t> cookie,
                                                std::string_view client_name,
                                                std::span<const uint8_t> client_key = {});
std::span<const uint8_t> write_heartbeat(PacketWriter& w, uint32_t session, uint32_t client_time_ms);
std::span<const uint8_t> write_disconnect(PacketWriter& w, uint32_t session);
std::span<const uint8_t> write_stats_request(PacketWriter& w, uint32_t session);
std::span<const uint8_t> write_tree_request(PacketWriter& w, uint32_t session);
std::span<const uint8_t> write_scene_request(PacketWriter& w, uint32_t session, uint32_t offset);

}  // namespace foresight::protocol

// packet_read: the trust boundary. Every way a datagram can be bad is dropped with its own
// reason, before anything in it is read.
#include "protocol/packet.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace foresight::protocol {
namespace {

std::vector<uint8_t> copy(std::span<const uint8_t> bytes) { return {bytes.begin(), bytes.end()}; }

std::vector<uint8_t> valid_heartbeat() {
  PacketWriter w;
  return copy(write_heartbeat(w, 7, 1234));
}

DropReason read_reason(std::span<const uint8_t> bytes) {
  DropReason reason = DropReason::kNone;
  const wire::Packet* p = packet_read(bytes, reason);
  EXPECT_EQ(p == nullptr, reason != DropReason::kNone);
  return reason;
}

TEST(PacketRead, AcceptsAValidPacket) {
  const auto bytes = valid_heartbeat();
  DropReason reason = DropReason::kMalformed;
  const wire::Packet* p = packet_read(bytes, reason);
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(reason, DropReason::kNone);
  ASSERT_EQ(p->message_type(), wire::Message::Heartbeat);
  EXPECT_EQ(p->message_as_Heartbeat()->session(), 7u);
  EXPECT_EQ(p->message_as_Heartbeat()->client_time_ms(), 1234u);
}

TEST(PacketRead, RejectsAnEmptyDatagram) {
  EXPECT_EQ(read_reason({}), DropReason::kTooSmall);
  const uint8_t seven[7] = {};
  EXPECT_EQ(read_reason(seven), DropReason::kTooSmall);
}

TEST(PacketRead, RejectsEveryTruncation) {
  const auto bytes = valid_heartbeat();
  for (size_t n = 0; n < bytes.size(); ++n) {
    const DropReason r = read_reason({bytes.data(), n});
    EXPECT_NE(r, DropReason::kNone) << "cut to " << n << " of " << bytes.size();
    if (n < 8) {
      EXPECT_EQ(r, DropReason::kTooSmall);
    }
  }
}

TEST(PacketRead, RejectsAWrongIdentifier) {
  auto bytes = valid_heartbeat();
  bytes[4] = 'X';  // "FSG1" sits right after the root offset
  EXPECT_EQ(read_reason(bytes), DropReason::kBadIdentifier);
}

TEST(PacketRead, RejectsOversizedDatagrams) {
  auto bytes = valid_heartbeat();
  bytes.resize(kMaxDatagramBytes + 1, 0);
  EXPECT_EQ(read_reason(bytes), DropReason::kTooLarge);
  bytes.resize(kMaxDatagramBytes);  // trailing zeros within the budget are harmless
  EXPECT_EQ(read_reason(bytes), DropReason::kNone);
}

TEST(PacketRead, RejectsAPacketWithoutMessage) {
  flatbuffers::FlatBufferBuilder fbb;
  wire::FinishPacketBuffer(fbb, wire::CreatePacket(fbb));
  EXPECT_EQ(read_reason({fbb.GetBufferPointer(), fbb.GetSize()}), DropReason::kEmpty);
}

TEST(PacketRead, RejectsAnOffsetPointingOutside) {
  auto bytes = valid_heartbeat();
  bytes[0] = 0xF0;  // root offset far past the end
  bytes[1] = 0xFF;
  EXPECT_EQ(read_reason(bytes), DropReason::kMalformed);
}

TEST(PacketRead, NeverAcceptsRandomGarbage) {
  std::mt19937_64 rng(12345);
  for (int i = 0; i < 20000; ++i) {
    std::vector<uint8_t> bytes(8 + rng() % 300);
    for (auto& b : bytes) b = static_cast<uint8_t>(rng());
    // Half with the right identifier, so the Verifier itself is exercised.
    if (i % 2 == 0) std::copy_n(wire::PacketIdentifier(), 4, bytes.begin() + 4);
    DropReason reason = DropReason::kNone;
    const wire::Packet* p = packet_read(bytes, reason);
    if (p != nullptr) {
      // Astronomically unlikely, but if random bytes verify they must still be readable.
      EXPECT_NE(p->message_type(), wire::Message::NONE);
    } else {
      EXPECT_NE(reason, DropReason::kNone);
      if (i % 2 == 1) {
        EXPECT_TRUE(reason == DropReason::kBadIdentifier || reason == DropReason::kMalformed);
      }
    }
  }
}

TEST(PacketRead, RejectsBitFlipsOfAValidPacketOrReadsThemSafely) {
  // Every single-bit corruption either fails verification or yields a packet that is safe to
  // read (verified): nothing in between.
  const auto good = valid_heartbeat();
  for (size_t bit = 0; bit < good.size() * 8; ++bit) {
    auto bytes = good;
    bytes[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
    DropReason reason = DropReason::kNone;
    const wire::Packet* p = packet_read(bytes, reason);
    if (p != nullptr && p->message_type() == wire::Message::Heartbeat) {
      (void)p->message_as_Heartbeat()->session();
    }
  }
}

TEST(DropCounters, CountByReason) {
  DropCounters c;
  c.add(DropReason::kMalformed);
  c.add(DropReason::kMalformed);
  c.add(DropReason::kTooLarge);
  EXPECT_EQ(c.total(), 3u);
  EXPECT_EQ(c.by_reason[static_cast<size_t>(DropReason::kMalformed)], 2u);
  EXPECT_STREQ(drop_reason_name(DropReason::kTooLarge), "too_large");
}

}  // namespace
}  // namespace foresight::protocol

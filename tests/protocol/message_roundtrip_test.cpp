// Built messages survive the trip through bytes and packet_read unchanged: the control messages,
// an Input with its redundant commands, and a multi-avatar Snapshot.
#include "protocol/avatar_delta.hpp"
#include "protocol/input_packet.hpp"
#include "protocol/packet.hpp"
#include "protocol/quantize.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace foresight::protocol {
namespace {

/// The message of type T in `bytes`, or nullptr (with a test failure saying why).
template <typename T>
const T* read_ok(std::span<const uint8_t> bytes) {
  DropReason reason = DropReason::kNone;
  const wire::Packet* p = packet_read(bytes, reason);
  EXPECT_NE(p, nullptr) << drop_reason_name(reason);
  return p ? p->message_as<T>() : nullptr;
}

TEST(MessageRoundTrip, ConnectRequestIsPaddedAndCarriesVersionHashAndName) {
  PacketWriter w;
  const auto bytes = write_connect_request(w, 0xfeedbeefcafef00dull, "bot-7");
  EXPECT_GE(bytes.size(), kMinConnectRequestBytes);
  EXPECT_LE(bytes.size(), kMaxDatagramBytes);
  const auto* m = read_ok<wire::ConnectRequest>(bytes);
  ASSERT_NE(m, nullptr);
  EXPECT_EQ(m->protocol(), kProtocolVersion);
  EXPECT_EQ(m->library_hash(), 0xfeedbeefcafef00dull);
  EXPECT_EQ(m->client_name()->str(), "bot-7");
}

TEST(MessageRoundTrip, ConnectResponseEchoesTheCookie) {
  PacketWriter w;
  const uint8_t cookie[8] = {1, 2, 3, 4, 5, 6, 7, 8};
  const auto* m = read_ok<wire::ConnectResponse>(write_connect_response(w, 99, cookie, "x"));
  ASSERT_NE(m, nullptr);
  ASSERT_EQ(m->cookie()->size(), 8u);
  EXPECT_TRUE(std::equal(cookie, cookie + 8, m->cookie()->begin()));
  EXPECT_EQ(m->library_hash(), 99u);
}

TEST(MessageRoundTrip, SmallControlMessages) {
  PacketWriter w;
  const auto* d = read_ok<wire::Disconnect>(write_disconnect(w, 5));
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->session(), 5u);
  const auto* sr = read_ok<wire::StatsRequest>(write_stats_request(w, 6));
  ASSERT_NE(sr, nullptr);
  EXPECT_EQ(sr->session(), 6u);
  const auto* hb = read_ok<wire::Heartbeat>(write_heartbeat(w, 8, 9));
  ASSERT_NE(hb, nullptr);
  EXPECT_EQ(hb->session(), 8u);
  EXPECT_EQ(hb->client_time_ms(), 9u);
}

TEST(MessageRoundTrip, InputKeepsTheNewestCommandsInOrder) {
  std::vector<wire::InputCommand> commands;
  for (uint32_t s = 1; s <= 11; ++s) {
    ControlInput in;
    in.camera_dir = vec2(0.0f, s % 2 ? 1.0f : -1.0f);
    in.camera_yaw_rad = 0.1f * static_cast<float>(s);
    in.crouch = s == 11;
    commands.push_back(input_command_from(in, s));
  }
  PacketWriter w;
  const auto bytes = write_input(w, 3, 77, 4242, commands);
  EXPECT_LE(bytes.size(), kMaxDatagramBytes);
  const auto* m = read_ok<wire::Input>(bytes);
  ASSERT_NE(m, nullptr);
  EXPECT_EQ(m->session(), 3u);
  EXPECT_EQ(m->ack_snapshot(), 77u);
  EXPECT_EQ(m->client_time_ms(), 4242u);
  ASSERT_EQ(m->commands()->size(), static_cast<size_t>(kInputRedundancy));
  for (uint32_t i = 0; i < m->commands()->size(); ++i) {
    const wire::InputCommand* c = m->commands()->Get(i);
    const wire::InputCommand& sent = commands[commands.size() - kInputRedundancy + i];
    EXPECT_EQ(c->sequence(), sent.sequence());  // newest last
    EXPECT_EQ(c->camera_yaw(), sent.camera_yaw());
    EXPECT_EQ(c->dir_y(), sent.dir_y());
    EXPECT_EQ(c->buttons(), sent.buttons());
  }
  EXPECT_EQ(m->commands()->Get(kInputRedundancy - 1)->sequence(), 11u);
}

TEST(MessageRoundTrip, SnapshotWithManyAvatarsFitsAndRoundTrips) {
  // Packed whole (the client acknowledged nothing): ~100 bits each, so 45 fit with room to spare.
  std::vector<wire::AvatarState> avatars;
  for (uint32_t i = 0; i < 45; ++i) {
    avatars.emplace_back(i + 1, quantize_mm(1.5f * static_cast<float>(i)), quantize_mm(-2.25f),
                         static_cast<int32_t>(i) - 1, static_cast<uint16_t>(i * 3),
                         quantize_angle(0.3f * static_cast<float>(i)), static_cast<uint8_t>(i % 30),
                         i == 4 ? kAvatarYours : kAvatarNone, 0);
  }
  std::vector<uint8_t> packed;
  pack_avatars(avatars, packed);
  PacketWriter w;
  auto& fbb = w.begin();
  const auto bytes = w.finish(wire::CreateSnapshot(fbb, 1000, 1, 3, 55, 66, 77, 0, 0, 0,
                                                   static_cast<uint16_t>(avatars.size()), fbb.CreateVector(packed)));
  EXPECT_LE(bytes.size(), kMaxDatagramBytes);
  const auto* m = read_ok<wire::Snapshot>(bytes);
  ASSERT_NE(m, nullptr);
  EXPECT_EQ(m->tick(), 1000u);
  EXPECT_EQ(m->part(), 1);
  EXPECT_EQ(m->parts(), 3);
  EXPECT_EQ(m->ack_input(), 55u);
  EXPECT_EQ(m->echo_client_time_ms(), 66u);
  EXPECT_EQ(m->server_time_ms(), 77u);
  std::vector<wire::AvatarState> decoded;
  ASSERT_EQ(snapshot_avatars(*m, AvatarHistory{}, decoded), AvatarDecodeStatus::kOk);
  ASSERT_EQ(decoded.size(), avatars.size());
  for (uint32_t i = 0; i < avatars.size(); ++i) {
    const wire::AvatarState* a = &decoded[i];
    EXPECT_EQ(a->id(), avatars[i].id());
    EXPECT_EQ(a->start_x_mm(), avatars[i].start_x_mm());
    EXPECT_EQ(a->start_z_mm(), avatars[i].start_z_mm());
    EXPECT_EQ(a->transition(), avatars[i].transition());
    EXPECT_EQ(a->segment(), avatars[i].segment());
    EXPECT_EQ(a->start_heading(), avatars[i].start_heading());
    EXPECT_EQ(a->frame(), avatars[i].frame());
    EXPECT_EQ(a->flags(), avatars[i].flags());
  }
  EXPECT_NEAR(dequantize_mm(decoded[3].start_x_mm()), 4.5f, 1e-6f);
}

}  // namespace
}  // namespace foresight::protocol

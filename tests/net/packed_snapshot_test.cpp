// Delta-coded snapshots over a real server (issue 8): a client that acknowledges what it gets
// (so the server codes avatars against those snapshots) decodes, through loss, duplicates and
// reordering, exactly the avatars a client that acknowledges nothing gets whole; and the packed
// snapshots are a fraction of the plain ones' size.
#include "bot_match.hpp"

#include <gtest/gtest.h>

#include <map>

namespace foresight {
namespace {

using namespace std::chrono_literals;
using test::snapshot_avatars;

// The fields both receivers must agree on (kAvatarYours differs: each has its own avatar).
bool same_world_state(const wire::AvatarState& a, const wire::AvatarState& b) {
  const uint8_t theirs = static_cast<uint8_t>(~protocol::kAvatarYours);
  return a.id() == b.id() && a.start_x_mm() == b.start_x_mm() && a.start_z_mm() == b.start_z_mm() &&
         a.transition() == b.transition() && a.segment() == b.segment() && a.start_heading() == b.start_heading() &&
         a.frame() == b.frame() && (a.flags() & theirs) == (b.flags() & theirs);
}

TEST(PackedSnapshots, AnAcknowledgingClientDecodesExactlyWhatAWholeStateClientGets) {
  test::BotMatch m(test::test_server_config("arena"), 6, bots::BotScript::kGoals, 3);
  bots::BotFleet fleet(m.server.library(), m.config);
  ASSERT_TRUE(fleet.ok()) << fleet.error();

  protocol::ClientConfig cc;
  cc.impairment.loss = 0.10, cc.impairment.duplicate = 0.05, cc.impairment.reorder = 0.05;
  cc.impairment.latency_ms = 20, cc.impairment.jitter_ms = 15, cc.impairment.seed = 5;
  protocol::ClientConnection delta(cc);
  protocol::Endpoint endpoint;
  std::string error;
  ASSERT_TRUE(protocol::parse_endpoint("127.0.0.1:" + std::to_string(m.server.port()), endpoint, error));
  ASSERT_TRUE(delta.start(endpoint, m.server.library().content_hash, "delta", m.now));
  test::RawClient whole(m.server.port());
  ASSERT_TRUE(whole.connect(m.server, m.now, m.server.library().content_hash));

  // By the server's time of the snapshot: each client numbers its own snapshots, and the server
  // serves the two on their own ticks (a third of the ticks serve both).
  std::map<uint32_t, std::vector<wire::AvatarState>> whole_by_snapshot, delta_by_snapshot;
  std::map<uint32_t, int> whole_parts;
  size_t whole_bytes = 0, whole_states = 0;
  uint32_t seq = 1, last_acked = 0;
  for (int frame = 0; frame < 30 * 20; ++frame) {
    m.play(fleet, 1);
    delta.update(m.now);
    if (delta.acked_snapshot() != last_acked) {
      last_acked = delta.acked_snapshot();
      std::vector<wire::AvatarState> avatars(delta.avatars().begin(), delta.avatars().end());
      std::sort(avatars.begin(), avatars.end(), [](const auto& a, const auto& b) { return a.id() < b.id(); });
      delta_by_snapshot[delta.snapshot_server_ms()] = std::move(avatars);
    }
    whole.send_input(vec2(0.0f), seq++);
    for (auto& d : whole.receive_all()) {
      protocol::DropReason reason;
      const wire::Packet* p = protocol::packet_read(d, reason);
      if (!p || p->message_type() != wire::Message::Snapshot) continue;
      const wire::Snapshot& s = *p->message_as_Snapshot();
      for (const wire::AvatarState& a : snapshot_avatars(s)) whole_by_snapshot[s.server_time_ms()].push_back(a);
      ++whole_parts[s.tick()];
      whole_bytes += d.size() + protocol::kSealOverheadBytes;  // receive_all() opened it
      whole_states += s.avatar_count();
    }
  }
  ASSERT_TRUE(delta.connected());
  EXPECT_EQ(delta.drops().by_reason[size_t(protocol::DropReason::kMissingBaseline)], 0u);
  EXPECT_EQ(delta.drops().by_reason[size_t(protocol::DropReason::kInvalidInput)], 0u);

  int compared = 0;
  for (const auto& [snapshot, avatars] : delta_by_snapshot) {
    const auto it = whole_by_snapshot.find(snapshot);
    if (it == whole_by_snapshot.end()) continue;
    std::vector<wire::AvatarState> expected = it->second;
    std::sort(expected.begin(), expected.end(), [](const auto& a, const auto& b) { return a.id() < b.id(); });
    ASSERT_EQ(avatars.size(), expected.size()) << "snapshot " << snapshot;
    for (size_t i = 0; i < avatars.size(); ++i)
      EXPECT_TRUE(same_world_state(avatars[i], expected[i])) << "snapshot " << snapshot << ", avatar " << expected[i].id();
    ++compared;
  }
  // 20 s, 600 ticks: each client is served on two ticks of three, both on at least a third of
  // them (200), less the 10 % lost on the way down.
  EXPECT_GT(compared, 140);
  EXPECT_EQ(m.server.num_players(), 8);
  // Seven of the eight acknowledge (the bots and the delta client): most avatars went delta-coded.
  EXPECT_GT(m.server.counters().avatars_referenced, m.server.counters().avatars_sent / 2);

  // Whole states (what an unacknowledged client gets) against what the acknowledging one
  // received: the delta-coded link carries far fewer bytes for the same snapshots.
  const double whole_per_snapshot = static_cast<double>(whole_bytes) / static_cast<double>(whole_parts.size());
  const double delta_per_snapshot = static_cast<double>(delta.bytes_received()) / static_cast<double>(delta.snapshot_ticks());
  std::printf("8 avatars: %.0f bytes a snapshot whole (%zu states), %.0f delta-coded (sealing included; the delta figure also counts the few other messages)\n", whole_per_snapshot,
              whole_states, delta_per_snapshot);
  // With 8 avatars most of a datagram is the same either way (sealing, the Snapshot table, its
  // other fields, and the delta figure counts the other messages too): 0.80 of whole was the
  // margin until the references' snapshots-back field grew from 4 to 6 bits (protocol 8), then
  // 212.6 against 212.4 bytes. Bytes per avatar are checked in avatar_delta_test.cpp.
  EXPECT_LT(delta_per_snapshot, 0.85 * whole_per_snapshot);
  fleet.disconnect_all();
}

}  // namespace
}  // namespace foresight

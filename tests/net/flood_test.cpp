// A flood of bogus connects (issue 8): 10,000 ConnectRequests a second from 64 addresses, plus
// forged ConnectResponses and garbage, while three real bots play. The server stays playable (the
// bots connect and walk), answers at most max_challenges_per_tick challenges a tick, keeps no
// state for anyone who has not proven its address (stateless cookies), and its memory stays flat.
#include "bot_match.hpp"

#include "protocol/packet.hpp"

#include <gtest/gtest.h>

#include <cstdio>

#include <fstream>
#include <memory>

namespace foresight {
namespace {

long rss_kib() {
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  statm >> pages >> resident;
  return resident * 4;  // 4 KiB pages
}

TEST(Flood, TenThousandBogusConnectsASecondLeaveTheServerPlayable) {
  server::ServerConfig sc = test::test_server_config("arena");
  sc.max_challenges_per_tick = 64;
  test::BotMatch m(sc, 3, bots::BotScript::kWander);
  bots::BotFleet fleet(m.server.library(), m.config);
  ASSERT_TRUE(fleet.ok());
  std::vector<std::unique_ptr<test::RawClient>> flooders;
  for (int i = 0; i < 64; ++i) flooders.push_back(std::make_unique<test::RawClient>(m.server.port()));
  protocol::PacketWriter w;
  const auto request = protocol::write_connect_request(w, m.server.library().content_hash, "flood");
  const std::vector<uint8_t> connect(request.begin(), request.end());
  const std::array<uint8_t, 16> forged_cookie{9, 9, 9};
  const auto response = protocol::write_connect_response(w, m.server.library().content_hash, forged_cookie, "flood");
  const std::vector<uint8_t> forged(response.begin(), response.end());
  const std::vector<uint8_t> garbage(300, 0x5A);

  // The bots connect first and play 5 s, so their trees' node pools (which grow with the work:
  // motion_tree.hpp) have reached their working size before memory is measured.
  m.play(fleet, 150);
  const long rss_before = rss_kib();
  const uint64_t sent_before = m.server.counters().challenges_sent;
  // 10 s of flood: 333 connects, 30 forged responses and 30 garbage datagrams per 33 ms tick.
  int ticks = 0;
  for (; ticks < 30 * 10; ++ticks) {
    for (int k = 0; k < 333; ++k) flooders[static_cast<size_t>(k % 64)]->send_raw(connect);
    for (int k = 0; k < 30; ++k) flooders[static_cast<size_t>(k % 64)]->send_raw(forged);
    for (int k = 0; k < 30; ++k) flooders[static_cast<size_t>(k % 64)]->send_raw(garbage);
    m.play(fleet, 1);
    if (ticks % 30 == 0)
      for (auto& f : flooders) f->receive_all();  // keep the flooders' sockets from filling
  }
  const auto& c = m.server.counters();
  EXPECT_EQ(fleet.connected_now(), 3);
  EXPECT_EQ(m.server.num_players(), 3) << "no bogus session";
  EXPECT_GT(fleet.report(m.now).walked_m_mean, 5.0) << "the bots kept playing";
  // Unproven addresses get at most max_challenges_per_tick answers a tick (challenges and
  // bad-cookie refusals together): the server is no amplifier, whatever the flood.
  EXPECT_LE(c.challenges_sent - sent_before + c.refused, static_cast<uint64_t>(ticks) * 64u);
  EXPECT_GT(c.challenges_capped, 30000u) << "most of the flood was ignored by the cap";
  EXPECT_GE(c.drops.by_reason[static_cast<size_t>(protocol::DropReason::kBadIdentifier)], 30u * 300u);
  EXPECT_EQ(c.sessions_opened, 3u);
  // Stateless: the flood leaves no per-address state behind; allow a little for allocator noise.
  // Not under AddressSanitizer: freed memory waits in its quarantine (256 MB) before reuse, so
  // there the resident set grows with every allocation the tick makes and frees (tree pools
  // resizing, a compaction's scratch), not with state kept.
  const long grew_kib = rss_kib() - rss_before;
  std::printf("resident memory grew by %ld KiB during the flood\n", grew_kib);
#if !defined(__SANITIZE_ADDRESS__)
  EXPECT_LT(grew_kib, 8 * 1024);
#endif
  fleet.disconnect_all();
}

}  // namespace
}  // namespace foresight

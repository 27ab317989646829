// Interest management (server/interest.hpp): the grid finds exactly the avatars within the radius
// (checked against brute force), a client gets the near ones every snapshot and the far ones only
// when due, flagged; and a real server with a small radius sends a far avatar every far_every-th
// snapshot while a near one is in all of them.
#include "interest.hpp"
#include "raw_client.hpp"

#include "math/splitmix64.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace foresight {
namespace {

using namespace std::chrono_literals;
using test::snapshot_avatars;

TEST(Interest, TheGridFindsExactlyWhoIsNear) {
  SplitMix64 rng{5};
  std::vector<vec2> positions(2000);
  for (vec2& p : positions) p = {rng.uniform(-100.0f, 100.0f), rng.uniform(-100.0f, 100.0f)};
  server::InterestGrid grid;
  grid.build(positions, 12.0f);
  std::vector<uint32_t> found, far_index;
  std::vector<uint8_t> far;
  for (uint32_t own = 0; own < 200; ++own) {
    found.clear();
    grid.near(positions[own], 12.0f, found);
    std::sort(found.begin(), found.end());
    std::vector<uint32_t> brute;
    for (uint32_t i = 0; i < positions.size(); ++i)
      if (glm::length(positions[i] - positions[own]) <= 12.0f) brute.push_back(i);
    ASSERT_EQ(found, brute) << own;
    // Not due: the near ones (own included); due: everyone, the far ones flagged.
    server::select_interest(grid, positions, own, 12.0f, false, 0.0f, far_index, far);
    EXPECT_EQ(far_index, brute);
    EXPECT_EQ(far, std::vector<uint8_t>(brute.size(), 0)) << "near ones are never far";
    server::select_interest(grid, positions, own, 12.0f, true, 0.0f, far_index, far);
    ASSERT_EQ(far_index.size(), positions.size());
    ASSERT_EQ(far.size(), far_index.size());
    for (uint32_t k = 0; k < far_index.size(); ++k)
      EXPECT_EQ(far[k] != 0, !std::binary_search(brute.begin(), brute.end(), far_index[k])) << far_index[k];
    // Due with a far radius of 30 m (cells of 12: the grid looks 3 cells out): only those within it.
    std::vector<uint32_t> within;
    for (uint32_t i = 0; i < positions.size(); ++i)
      if (glm::length(positions[i] - positions[own]) <= 30.0f) within.push_back(i);
    server::select_interest(grid, positions, own, 12.0f, true, 30.0f, far_index, far);
    ASSERT_EQ(far_index, within) << own;
    ASSERT_EQ(far.size(), far_index.size());
    for (uint32_t k = 0; k < far_index.size(); ++k)
      EXPECT_EQ(far[k] != 0, !std::binary_search(brute.begin(), brute.end(), far_index[k])) << far_index[k];
  }
}

TEST(Interest, AFarAvatarComesEveryFewSnapshotsANearOneInAll) {
  server::ServerConfig config = test::test_server_config("arena");
  config.interest_radius_m = 3.0f;
  config.far_every = 4;
  server::Server server;
  std::string error;
  ASSERT_TRUE(server.start(config, error)) << error;
  auto now = server::Clock::now();
  test::RawClient a(server.port()), b(server.port()), c(server.port());
  ASSERT_TRUE(a.connect(server, now, server.library().content_hash));
  ASSERT_TRUE(b.connect(server, now, server.library().content_hash));
  ASSERT_TRUE(c.connect(server, now, server.library().content_hash));
  // b walks away (camera-space forward along its facing); a and c stay together.
  const float facing = server.avatar(b.avatar)->root().heading_rad;
  uint32_t seq = 1;
  for (int i = 0; i < 30 * 8 && glm::length(server.avatar(b.avatar)->root().pos_m - server.avatar(a.avatar)->root().pos_m) < 6.0f;
       ++i) {
    b.send_input(vec2(0.0f, 1.0f), seq++, facing);
    a.send_input(vec2(0.0f), seq);
    c.send_input(vec2(0.0f), seq);
    server.run_tick(now += 33ms);
  }
  ASSERT_GT(glm::length(server.avatar(b.avatar)->root().pos_m - server.avatar(a.avatar)->root().pos_m), 4.0f);
  ASSERT_LT(glm::length(server.avatar(c.avatar)->root().pos_m - server.avatar(a.avatar)->root().pos_m), 2.5f);
  a.receive_all();
  int snapshots = 0, with_far = 0, with_near = 0, far_flagged = 0;
  for (int i = 0; i < 60; ++i) {
    b.send_input(vec2(0.0f), seq);
    a.send_input(vec2(0.0f), seq);
    c.send_input(vec2(0.0f), seq++);
    server.run_tick(now += 33ms);
    for (auto& d : a.receive_all()) {
      protocol::DropReason reason;
      const wire::Packet* p = protocol::packet_read(d, reason);
      const wire::Snapshot* s = p ? p->message_as_Snapshot() : nullptr;
      if (!s || s->avatar_count() == 0) continue;
      ++snapshots;
      for (const wire::AvatarState& st : snapshot_avatars(*s)) {
        if (st.id() == b.avatar) {
          ++with_far;
          far_flagged += (st.flags() & protocol::kAvatarFar) != 0;
        }
        with_near += st.id() == c.avatar;
      }
    }
  }
  ASSERT_GT(snapshots, 30);
  EXPECT_EQ(with_near, snapshots) << "the near avatar is in every snapshot";
  EXPECT_EQ(far_flagged, with_far) << "and the far one is flagged far";
  EXPECT_NEAR(with_far, snapshots / 4, 2) << "the far one in every 4th";
}

}  // namespace
}  // namespace foresight

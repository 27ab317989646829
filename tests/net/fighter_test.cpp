// NPC fighters in a real server (loopback UDP, the test's own clock): they spawn from the scene,
// follow the nearest player with the look-ahead, stop in reach, and are sent as NPC avatars.
#include "anim/fk.hpp"
#include "fighter/morphology.hpp"
#include "protocol/quantize.hpp"
#include "raw_client.hpp"
#include "support/test_paths.hpp"

#include <gtest/gtest.h>

#include <thread>

namespace foresight {
namespace {

using test::RawClient;
using test::snapshot_avatars;
using namespace std::chrono_literals;

struct Arena {
  server::Server server;
  server::Clock::time_point now = server::Clock::now();
  explicit Arena(int fighters, bool auto_attack, int morphology = -1) {
    server::ServerConfig config = test::test_server_config("arena");
    config.fighter_morphology = morphology;
    config.fighters = fighters;
    config.fighters_auto_attack = auto_attack;
    std::string error;
    EXPECT_TRUE(server.start(config, error)) << error;
  }
  void ticks(int n, RawClient& c, uint32_t& seq) {
    for (int i = 0; i < n; ++i) {
      c.send_input(vec2(0.0f), seq++, 0.0f);  // standing still, and keeping the session alive
      server.run_tick(now += 33ms);
    }
  }
};

TEST(Fighter, SpawnsFromTheSceneAndFollowsThePlayerIntoReach) {
  Arena a(-1, /*auto_attack=*/false);
  ASSERT_GE(a.server.num_fighters(), 1) << "the arena scene has NPC spawns";
  EXPECT_EQ(a.server.num_players(), 0);
  RawClient c(a.server.port());
  ASSERT_TRUE(c.connect(a.server, a.now, a.server.library().content_hash));
  EXPECT_EQ(a.server.num_players(), 1);
  const uint32_t fighter = a.server.fighter_ids().front();
  const vec2 player = a.server.avatar(c.avatar)->root().pos_m;
  const float start = glm::length(a.server.avatar(fighter)->root().pos_m - player);
  uint32_t seq = 1;
  a.ticks(360, c, seq);  // 12 s
  const float end = glm::length(a.server.avatar(fighter)->root().pos_m - a.server.avatar(c.avatar)->root().pos_m);
  EXPECT_GT(start, 2.0f);
  EXPECT_LT(end, 1.6f) << "from " << start << " m";
  EXPECT_EQ(a.server.counters().avatar_contacts, 0u);
  // Snapshots carry the fighters, flagged as NPCs.
  int npcs = 0;
  for (auto& d : c.receive_all()) {
    protocol::DropReason reason;
    const wire::Packet* p = protocol::packet_read(d, reason);
    if (p == nullptr || p->message_type() != wire::Message::Snapshot) continue;
    npcs = 0;
    for (const wire::AvatarState& s : snapshot_avatars(*p->message_as_Snapshot()))
      if (s.flags() & protocol::kAvatarNpc) ++npcs;
  }
  EXPECT_EQ(npcs, a.server.num_fighters());
}

TEST(Fighter, ExtraFightersForLoadTestsStartAtPlayerSpawns) {
  Arena a(8, false);
  EXPECT_EQ(a.server.num_fighters(), 8);
  EXPECT_EQ(a.server.num_players(), 0);
}

}  // namespace
}  // namespace foresight

namespace foresight {
namespace {

// Ticks until the fighter stands in reach of the player (the player holding still).
bool wait_in_reach(Arena& a, RawClient& c, uint32_t fighter, uint32_t& seq) {
  for (int i = 0; i < 600; ++i) {
    a.ticks(1, c, seq);
    const float d = glm::length(a.server.avatar(fighter)->root().pos_m - a.server.avatar(c.avatar)->root().pos_m);
    if (d < 1.2f && a.server.strike_events().empty()) {
      a.ticks(15, c, seq);  // let it settle into its stance
      return true;
    }
  }
  return false;
}

// The tall morphology (index 1): from the ~1 m two avatars' bodies keep between them, a short
// fighter cannot reach an adult's head (docs/FIGHTER.md), a tall one can with a punch and a kick.
constexpr int kTall = 1;

TEST(Fighter, HitsAStandingPlayerWhenOrdered) {
  Arena a(1, /*auto_attack=*/false, kTall);
  RawClient c(a.server.port());
  ASSERT_TRUE(c.connect(a.server, a.now, a.server.library().content_hash));
  const uint32_t fighter = a.server.fighter_ids().front();
  uint32_t seq = 1;
  ASSERT_TRUE(wait_in_reach(a, c, fighter, seq));
  for (server::StrikeOrder order : {server::StrikeOrder::kPunch, server::StrikeOrder::kKick}) {
    const size_t before = a.server.strike_events().size();
    ASSERT_TRUE(a.server.order_fighter(fighter, order));
    a.ticks(150, c, seq);  // 5 s: strike, cool-down
    ASSERT_EQ(a.server.strike_events().size(), before + 1) << "one strike per order";
    const server::StrikeEvent& e = a.server.strike_events().back();
    EXPECT_EQ(e.fighter, fighter);
    EXPECT_EQ(e.target, c.avatar);
    EXPECT_EQ(e.kick, order == server::StrikeOrder::kKick);
    EXPECT_TRUE(e.hit) << "missed by " << e.miss_m << " m (reach error " << e.reach_error_m << " m)";
  }
  EXPECT_EQ(a.server.counters().fighter_strike_failures, 0u);
  EXPECT_EQ(a.server.counters().avatar_contacts, 0u);
}

TEST(Fighter, MissesAPlayerWhoStepsAwayAfterTheOrder) {
  Arena a(1, /*auto_attack=*/false, kTall);
  RawClient c(a.server.port());
  ASSERT_TRUE(c.connect(a.server, a.now, a.server.library().content_hash));
  const uint32_t fighter = a.server.fighter_ids().front();
  uint32_t seq = 1;
  ASSERT_TRUE(wait_in_reach(a, c, fighter, seq));
  // The player walks away from the fighter; the kick is ordered once the step is under way (an
  // avatar leaves its idle clip only at the clip's end, up to 0.4 s after the key press), so the
  // head stored at the order is not where the head is when the foot arrives.
  const vec2 start = a.server.avatar(c.avatar)->root().pos_m;
  const vec2 away = start - a.server.avatar(fighter)->root().pos_m;
  const float yaw = std::atan2(away.x, away.y);
  bool ordered = false;
  for (int i = 0; i < 90 && a.server.strike_events().empty(); ++i) {
    c.send_input(vec2(0.0f, 1.0f), seq++, yaw);
    a.server.run_tick(a.now += 33ms);
    if (!ordered && glm::length(a.server.avatar(c.avatar)->root().pos_m - start) > 0.05f)
      ordered = a.server.order_fighter(fighter, server::StrikeOrder::kKick);
  }
  ASSERT_TRUE(ordered);
  ASSERT_EQ(a.server.strike_events().size(), 1u) << "the strike still happens";
  const server::StrikeEvent& e = a.server.strike_events().back();
  EXPECT_FALSE(e.hit) << "effector " << e.miss_m << " m from the head";
  EXPECT_GT(e.miss_m, 0.15f);
}

// The last snapshot this client received, if any (drains the socket).
std::optional<std::vector<uint8_t>> last_snapshot(RawClient& c) {
  std::optional<std::vector<uint8_t>> last;
  for (auto& d : c.receive_all()) {
    protocol::DropReason reason;
    const wire::Packet* p = protocol::packet_read(d, reason);
    if (p != nullptr && p->message_type() == wire::Message::Snapshot) last = std::move(d);
  }
  return last;
}

TEST(Fighter, SnapshotsCarryTheAdaptedPoseAndTheStrikeEvent) {
  Arena a(1, /*auto_attack=*/false, kTall);
  RawClient c(a.server.port());
  ASSERT_TRUE(c.connect(a.server, a.now, a.server.library().content_hash));
  const uint32_t fighter = a.server.fighter_ids().front();
  uint32_t seq = 1;
  ASSERT_TRUE(wait_in_reach(a, c, fighter, seq));
  ASSERT_TRUE(a.server.order_fighter(fighter, server::StrikeOrder::kPunch));
  const Morphology morphology = default_morphologies()[kTall];
  float worst_m = 0.0f;
  int poses_checked = 0;
  bool event_seen = false;
  for (int i = 0; i < 60; ++i) {
    a.ticks(1, c, seq);
    const auto snap = last_snapshot(c);
    if (!snap) continue;  // 20 snapshots a second at 30 ticks
    protocol::DropReason reason;
    const wire::Snapshot* s = protocol::packet_read(*snap, reason)->message_as_Snapshot();
    ASSERT_NE(s->fighters(), nullptr);
    ASSERT_EQ(s->fighters()->size(), 1u);
    const wire::FighterPose* f = s->fighters()->Get(0);
    EXPECT_EQ(f->avatar(), fighter);
    EXPECT_EQ(f->morphology(), kTall);
    // Rebuild the pose the way a client does and compare every joint with the server's.
    const int n = morphology.skeleton.num_joints();
    ASSERT_EQ(static_cast<int>(f->rotations()->size()), n);
    std::vector<vec3> local_pos = morphology.skeleton.rest_offsets_m, global_pos(static_cast<size_t>(n));
    std::vector<quat> local_rot(static_cast<size_t>(n)), global_rot(static_cast<size_t>(n));
    local_pos[0] = vec3(protocol::dequantize_mm(f->pelvis_x_mm()), protocol::dequantize_mm(f->pelvis_y_mm()),
                        protocol::dequantize_mm(f->pelvis_z_mm()));
    for (int j = 0; j < n; ++j) local_rot[static_cast<size_t>(j)] = protocol::dequantize_rotation(f->rotations()->Get(j));
    fk_pose(morphology.skeleton, local_pos, local_rot, global_pos, global_rot);
    const PoseBuffers* server_pose = a.server.fighter_pose(fighter);
    ASSERT_NE(server_pose, nullptr);
    for (int j = 0; j < n; ++j)
      worst_m = std::max(worst_m, glm::length(global_pos[static_cast<size_t>(j)] - server_pose->global_pos_m[static_cast<size_t>(j)]));
    ++poses_checked;
    if (s->events() != nullptr && s->events()->size() > 0) {
      const wire::StrikeEventState* e = s->events()->Get(0);
      EXPECT_EQ(e->fighter(), fighter);
      EXPECT_EQ(e->target(), c.avatar);
      EXPECT_EQ(e->hit(), a.server.strike_events().back().hit);
      event_seen = true;
    }
  }
  EXPECT_GT(poses_checked, 30);
  EXPECT_LT(worst_m, 0.01f) << "the client's rebuilt joints against the server's";
  EXPECT_TRUE(event_seen);
}

}  // namespace
}  // namespace foresight

namespace foresight {
namespace {

TEST(Fighter, SupervisorCommandsListOrderAndSwitchThePolicy) {
  Arena a(2, /*auto_attack=*/true);
  const auto text = [&](const std::string& line) { return a.server.admin_command(line).text; };
  const auto status = [&](const std::string& line) { return a.server.admin_command(line).status; };
  const std::string list = text("fighters");
  EXPECT_NE(list.find("2 fighters"), std::string::npos) << list;
  EXPECT_NE(list.find("sparring-partner"), std::string::npos) << list;
  // No player yet: nobody to strike at.
  EXPECT_NE(text("order all kick").find("ordered kick to 0 of 2"), std::string::npos);
  RawClient c(a.server.port());
  ASSERT_TRUE(c.connect(a.server, a.now, a.server.library().content_hash));
  uint32_t seq = 1;
  a.ticks(2, c, seq);  // the fighters pick the player as their target
  EXPECT_NE(text("order all kick").find("ordered kick to 2 of 2"), std::string::npos);
  const uint32_t id = a.server.fighter_ids().front();
  EXPECT_NE(text("order " + std::to_string(id) + " punch").find("to 1 of 1"), std::string::npos);
  EXPECT_EQ(status("order all kick"), 200);
  // Bad input gets a clear answer, a status saying what kind of mistake, and changes nothing.
  EXPECT_NE(text("order 9999 punch").find("no fighter"), std::string::npos);
  EXPECT_EQ(status("order 9999 punch"), 404);
  EXPECT_NE(text("order 1x punch").find("no fighter"), std::string::npos);
  EXPECT_NE(text("order all uppercut").find("usage"), std::string::npos);
  EXPECT_EQ(status("order all uppercut"), 400);
  EXPECT_NE(text("auto maybe").find("usage"), std::string::npos);
  EXPECT_NE(text("dance").find("unknown command"), std::string::npos);
  EXPECT_EQ(status("dance"), 404);
  // A word too many is a mistake, not ignored: the policy stays on.
  EXPECT_EQ(status("auto off now"), 400);
  EXPECT_EQ(status("fighters please"), 400);
  EXPECT_EQ(text(""), "");
  EXPECT_NE(text("auto off").find("off"), std::string::npos);
  // Queued from another thread, run on the next tick.
  std::thread([q = a.server.admin_queue()] { q->post("order all any"); }).join();
  a.server.run_tick(a.now += 33ms);
}

TEST(Fighter, OwnPolicyStrikesWithoutOrdersAndNotWhenSwitchedOff) {
  Arena on(1, /*auto_attack=*/true, kTall);
  RawClient c(on.server.port());
  ASSERT_TRUE(c.connect(on.server, on.now, on.server.library().content_hash));
  uint32_t seq = 1;
  on.ticks(600, c, seq);  // 20 s next to a standing player
  EXPECT_GE(on.server.strike_events().size(), 3u) << "a strike every cool-down (2.5 s) once in reach";

  Arena off(1, /*auto_attack=*/true, kTall);
  off.server.admin_command("auto off");
  RawClient d(off.server.port());
  ASSERT_TRUE(d.connect(off.server, off.now, off.server.library().content_hash));
  uint32_t seq2 = 1;
  off.ticks(600, d, seq2);
  EXPECT_TRUE(off.server.strike_events().empty());
}

}  // namespace
}  // namespace foresight

namespace foresight {
namespace {

// A server whose strike database also holds the captured strikes of ../shared/mocap/fighting
// (with the shipped sidecar) starts, and its strikes still reach the stored target.
TEST(Fighter, StrikesWithTheMocapStrikesInTheDatabase) {
  FORESIGHT_REQUIRE_MOCAP();
  server::Server server;
  server::ServerConfig config = test::test_server_config("arena");
  config.fighters = 1;
  config.fighters_auto_attack = false;
  config.fighter_morphology = kTall;
  config.fighter_strikes = (test::mocap_dir() / "fighting").string();
  config.fighter_strikes_sidecar = std::string(FORESIGHT_DATA_DIR) + "/fighter/bandai_fighting.strikes.json";
  std::string error;
  ASSERT_TRUE(server.start(config, error)) << error;
  ASSERT_NE(server.fighter_assets(), nullptr);
  EXPECT_GT(server.fighter_assets()->database.entries.size(), 16u + 10u) << "default strikes plus the captured ones";
  RawClient c(server.port());
  auto now = server::Clock::now();
  ASSERT_TRUE(c.connect(server, now, server.library().content_hash));
  uint32_t seq = 1;
  const uint32_t fighter = server.fighter_ids().front();
  auto tick = [&] {
    c.send_input(vec2(0.0f), seq++, 0.0f);
    server.run_tick(now += 33ms);
  };
  for (int i = 0; i < 600 && glm::length(server.avatar(fighter)->root().pos_m - server.avatar(c.avatar)->root().pos_m) > 1.2f; ++i) tick();
  for (int i = 0; i < 15; ++i) tick();
  int strikes = 0;
  for (server::StrikeOrder order : {server::StrikeOrder::kPunch, server::StrikeOrder::kKick, server::StrikeOrder::kAny}) {
    ASSERT_TRUE(server.order_fighter(fighter, order));
    for (int i = 0; i < 150; ++i) tick();
    ++strikes;
    ASSERT_EQ(server.strike_events().size(), static_cast<size_t>(strikes));
    EXPECT_LT(server.strike_events().back().reach_error_m, 0.05f);
  }
  EXPECT_EQ(server.counters().fighter_strike_failures, 0u);
}

}  // namespace
}  // namespace foresight

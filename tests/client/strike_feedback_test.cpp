// The client's bookkeeping of strike events (strike_feedback.hpp): counters, markers, flashes.
#include "support/alloc_counter.hpp"
#include "debug_overlay.hpp"
#include "strike_feedback.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace foresight::client {
namespace {

constexpr uint32_t kMe = 5, kBot = 6, kFighter = 20;

protocol::StrikeEventInfo strike(uint32_t seq, uint32_t target, bool hit, vec3 at = vec3(1, 1.6f, 2)) {
  protocol::StrikeEventInfo e;
  e.sequence = seq;
  e.fighter = kFighter;
  e.target = target;
  e.effector_m = at;
  e.hit = hit;
  e.miss_m = hit ? 0.05f : 0.4f;
  return e;
}

TEST(ClientStrikeFeedback, CountsHitsTakenAndDodgesOfTheLocalPlayerOnly) {
  StrikeFeedback fb;
  const std::vector<protocol::StrikeEventInfo> events = {strike(1, kMe, true), strike(2, kMe, false),
                                                         strike(3, kBot, true), strike(4, kMe, false)};
  fb.add(events, kMe, 10.0);
  EXPECT_EQ(fb.strikes_seen(), 4u);
  EXPECT_EQ(fb.hits_taken(), 1u);
  EXPECT_EQ(fb.dodged(), 2u);
  fb.clear_effects();  // a reconnect: the counters stay
  EXPECT_EQ(fb.hits_taken(), 1u);
  EXPECT_EQ(fb.markers_showing(10.5), 0);
}

TEST(ClientStrikeFeedback, FlashesAfterTheInterpolationDelayForFlashSeconds) {
  StrikeFeedbackConfig config;
  config.show_delay_s = 0.1;
  config.flash_s = 0.3;
  StrikeFeedback fb(config);
  const protocol::StrikeEventInfo hit = strike(1, kMe, true);
  fb.add({&hit, 1}, kMe, 2.0);
  EXPECT_EQ(fb.own_hit_flash(2.05), 0.0f) << "not before the strike is drawn";
  EXPECT_NEAR(fb.own_hit_flash(2.1), 1.0f, 1e-6f);
  EXPECT_NEAR(fb.own_hit_flash(2.25), 0.5f, 1e-5f);
  EXPECT_EQ(fb.own_hit_flash(2.41), 0.0f);
  // The target avatar flashes white for the same time; nobody else does.
  EXPECT_NEAR(fb.target_flash(kMe, 2.25), 0.5f, 1e-5f);
  EXPECT_EQ(fb.target_flash(kBot, 2.25), 0.0f);
  // A miss flashes nothing; a bot's hit flashes the bot, not our screen.
  const protocol::StrikeEventInfo miss = strike(2, kMe, false), bot_hit = strike(3, kBot, true);
  fb.add({&miss, 1}, kMe, 5.0);
  fb.add({&bot_hit, 1}, kMe, 5.0);
  EXPECT_EQ(fb.own_hit_flash(5.2), 0.0f);
  EXPECT_GT(fb.target_flash(kBot, 5.2), 0.0f);
  EXPECT_EQ(fb.target_flash(kMe, 5.2), 0.0f);
}

TEST(ClientStrikeFeedback, MarkersAtTheEffectorForMarkerSeconds) {
  StrikeFeedback fb;  // delay 0.1 s, markers 1 s
  const std::vector<protocol::StrikeEventInfo> events = {strike(1, kMe, true, vec3(1, 2, 3)),
                                                         strike(2, kBot, false, vec3(4, 5, 6))};
  fb.add(events, kMe, 1.0);
  EXPECT_EQ(fb.markers_showing(1.05), 0);
  EXPECT_EQ(fb.markers_showing(1.1), 2);
  std::vector<StrikeMarker> seen;
  std::vector<float> ages;
  fb.for_each_marker(1.6, [&](const StrikeMarker& m, float age) {
    seen.push_back(m);
    ages.push_back(age);
  });
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_EQ(seen[0].pos_m, vec3(1, 2, 3));
  EXPECT_TRUE(seen[0].hit);
  EXPECT_EQ(seen[1].pos_m, vec3(4, 5, 6));
  EXPECT_FALSE(seen[1].hit);
  EXPECT_NEAR(ages[0], 0.5f, 1e-5f);
  EXPECT_EQ(fb.markers_showing(2.11), 0);
}

TEST(ClientStrikeFeedback, KeepsTheNewestMarkersWithoutAllocating) {
  StrikeFeedback fb;
  std::vector<protocol::StrikeEventInfo> events;
  for (uint32_t i = 0; i < 100; ++i) events.push_back(strike(i + 1, kBot, i % 2 == 0, vec3(static_cast<float>(i), 0, 0)));
  test::AllocationCount count;
  fb.add(events, kMe, 0.0);
  int n = 0;
  float last_x = -1;
  fb.for_each_marker(0.5, [&](const StrikeMarker& m, float) {
    ++n;
    last_x = std::max(last_x, m.pos_m.x);
  });
  EXPECT_EQ(count.allocations(), 0);
  EXPECT_EQ(n, StrikeFeedback::kMaxMarkers);
  EXPECT_EQ(last_x, 99.0f);
  EXPECT_GT(fb.target_flash(kBot, 0.2), 0.0f);
}

TEST(ClientStrikeFeedback, TheOverlayLine) {
  FightFigures f;
  f.fighters = 5;
  f.hits_taken = 2;
  f.dodged = 7;
  char line[96];
  format_fight_line(f, line, sizeof line);
  EXPECT_STREQ(line, "fighters 5, hits taken 2, dodged 7");
}

}  // namespace
}  // namespace foresight::client

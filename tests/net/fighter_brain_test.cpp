// The fighter's decisions (paper Fig. 9) without animation: follow, stop in reach, strike on the
// own policy after the cool-down or on a supervisor's order, the target stored at the decision.
#include "fighters/fighter_brain.hpp"

#include <gtest/gtest.h>

namespace foresight::server {
namespace {

FighterSenses senses_at(double t, vec2 target, bool can_strike = true) {
  FighterSenses s;
  s.now_s = t;
  s.self_pos_m = vec2(0.0f);
  s.can_strike = can_strike;
  s.has_target = true;
  s.target_id = 7;
  s.target_pos_m = target;
  s.way_m = target;  // open ground: straight at it
  s.target_head_m = vec3(target.x, 1.6f, target.y);
  return s;
}

TEST(FighterBrain, FollowsAFarTargetAndStandsWithinReach) {
  FighterBrainConfig c;
  c.auto_attack = false;
  FighterBrain brain(c);
  FighterDecision d = brain.think(senses_at(0.0, vec2(0.0f, 5.0f)));
  EXPECT_EQ(brain.phase(), FighterPhase::kFollow);
  EXPECT_NEAR(d.move_world.y, 1.0f, 1e-5f);
  EXPECT_FALSE(d.strike);
  d = brain.think(senses_at(0.1, vec2(0.0f, 0.8f)));
  EXPECT_EQ(brain.phase(), FighterPhase::kRest);
  EXPECT_EQ(d.move_world, vec2(0.0f));
  // Hysteresis: just past reach it keeps standing; past reach + slack it follows again.
  d = brain.think(senses_at(0.2, vec2(0.0f, c.reach_m + 0.5f * c.follow_slack_m)));
  EXPECT_EQ(d.move_world, vec2(0.0f));
  d = brain.think(senses_at(0.3, vec2(0.0f, c.reach_m + 2.0f * c.follow_slack_m)));
  EXPECT_GT(d.move_world.y, 0.9f);
  // No target: rest.
  FighterSenses none = senses_at(0.4, vec2(0.0f, 5.0f));
  none.has_target = false;
  d = brain.think(none);
  EXPECT_EQ(d.move_world, vec2(0.0f));
  EXPECT_EQ(brain.phase(), FighterPhase::kRest);
}

TEST(FighterBrain, OwnPolicyStrikesInReachThenCoolsDown) {
  FighterBrainConfig c;
  c.cooldown_s = 2.0f;
  FighterBrain brain(c);
  // In reach but mid-step: not yet.
  EXPECT_FALSE(brain.think(senses_at(0.0, vec2(0.0f, 0.7f), false)).strike);
  const FighterDecision d = brain.think(senses_at(0.1, vec2(0.0f, 0.7f)));
  ASSERT_TRUE(d.strike);
  EXPECT_EQ(d.kind, StrikeOrder::kAny);
  EXPECT_EQ(d.target_id, 7u);
  EXPECT_FLOAT_EQ(d.target_head_m.y, 1.6f);
  EXPECT_EQ(brain.phase(), FighterPhase::kStrike);
  // While the strike plays nothing else is decided, orders included.
  brain.order(StrikeOrder::kKick, 0.2, 7, vec3(0.0f, 1.6f, 0.7f));
  EXPECT_FALSE(brain.think(senses_at(0.3, vec2(0.0f, 0.7f))).strike);
  brain.strike_finished(1.0);
  EXPECT_EQ(brain.phase(), FighterPhase::kRecover);
  EXPECT_FALSE(brain.think(senses_at(2.5, vec2(0.0f, 0.7f))).strike);  // cooling down (until 3.0)
  EXPECT_TRUE(brain.think(senses_at(3.1, vec2(0.0f, 0.7f))).strike);
}

TEST(FighterBrain, SupervisorOrderAimsWhereTheHeadWasWhenOrdered) {
  FighterBrainConfig c;
  c.auto_attack = false;
  FighterBrain brain(c);
  EXPECT_FALSE(brain.think(senses_at(0.0, vec2(0.0f, 0.7f))).strike);  // no policy, no order
  const vec3 head_then(0.0f, 1.6f, 0.7f);
  brain.order(StrikeOrder::kKick, 0.1, 7, head_then);
  // The player has moved since; the strike still goes where the head was.
  const FighterDecision d = brain.think(senses_at(0.2, vec2(0.5f, 0.9f)));
  ASSERT_TRUE(d.strike);
  EXPECT_EQ(d.kind, StrikeOrder::kKick);
  EXPECT_EQ(d.target_head_m, head_then);
  EXPECT_EQ(d.move_world, vec2(0.0f));
}

TEST(FighterBrain, AnOrderOutOfReachLapses) {
  FighterBrainConfig c;
  c.auto_attack = false;
  c.order_timeout_s = 1.0f;
  FighterBrain brain(c);
  brain.order(StrikeOrder::kPunch, 0.0, 7, vec3(0.0f, 1.6f, 4.0f));
  FighterDecision d = brain.think(senses_at(0.5, vec2(0.0f, 4.0f)));  // out of reach: follow
  EXPECT_FALSE(d.strike);
  EXPECT_GT(d.move_world.y, 0.9f);
  // Arrived, but the order is older than order_timeout_s: it lapsed.
  FighterSenses late = senses_at(1.5, vec2(0.0f, 0.8f));
  late.self_pos_m = vec2(0.0f, 3.5f);
  EXPECT_FALSE(brain.think(late).strike);
}

TEST(FighterBrain, WalksTowardsTheWayItIsGivenNotStraightAtTheTarget) {
  FighterBrain brain{FighterBrainConfig{}};
  FighterSenses s = senses_at(0.0, vec2(0.0f, 6.0f));
  s.way_m = vec2(3.0f, 0.0f);  // a route corner off to the side (a wall between)
  const FighterDecision d = brain.think(s);
  EXPECT_NEAR(d.move_world.x, 1.0f, 1e-5f);
  EXPECT_NEAR(d.move_world.y, 0.0f, 1e-5f);
}

}  // namespace
}  // namespace foresight::server

#pragma once
// What an NPC fighter decides each tick (paper Fig. 9): rest, follow the target player to stay
// within striking range, punch, kick. Orders come from a supervisor (an admin) or from its own
// policy (attack when in range once the cool-down is over). The target of a strike is the player's
// head where it was when the strike was decided: a player who moves or crouches in time is missed.
//
// Pure decisions, no animation: the fighter (fighter_npc.hpp) turns them into motion.
#include "math/types.hpp"

#include <cstdint>

namespace foresight::server {

enum class StrikeOrder : uint8_t { kNone = 0, kPunch = 1, kKick = 2, kAny = 3 };
enum class FighterPhase : uint8_t { kRest = 0, kFollow = 1, kStrike = 2, kRecover = 3 };

struct FighterBrainConfig {
  float reach_m = 1.1f;         ///< Ground distance to the target at which a strike can land.
  float follow_slack_m = 0.3f;  ///< Follows once farther than reach + slack; stops within reach.
  float cooldown_s = 2.5f;      ///< After a strike, before the own policy strikes again.
  float order_timeout_s = 4.0f; ///< An order not carried out by then (target out of reach) lapses.
  bool auto_attack = true;      ///< Own policy; false: only supervisor orders.
};

/// What the fighter perceives this tick.
struct FighterSenses {
  double now_s = 0;
  vec2 self_pos_m{0.0f};
  bool can_strike = false;   ///< Standing (between steps), so a strike can start now.
  bool has_target = false;
  uint32_t target_id = 0;
  vec2 target_pos_m{0.0f};   ///< The target's ground position.
  /// Where to walk to reach it: the target itself when the straight way is clear, else the next
  /// corner of a route around the walls (FighterNpc::way_to). Distances are still to the target.
  vec2 way_m{0.0f};
  vec3 target_head_m{0.0f};  ///< The target's head, world space.
};

struct FighterDecision {
  vec2 move_world{0.0f};  ///< Direction to walk (world ground); zero = stand.
  bool strike = false;    ///< Start a strike now.
  StrikeOrder kind = StrikeOrder::kNone;
  uint32_t target_id = 0;
  vec3 target_head_m{0.0f};  ///< Stored at the decision; never refreshed.
};

class FighterBrain {
 public:
  explicit FighterBrain(const FighterBrainConfig& config) : config_(config) {}

  /// A supervisor's order against `target_id`, whose head is at `target_head_m` now: that point is
  /// the strike's target (paper 3.5: stored when the attack is ordered, never refreshed). Ignored
  /// while a strike plays; carried out as soon as the point is within reach + follow_slack (an
  /// explicit order stretches a little further than the own policy) and the fighter stands;
  /// dropped after order_timeout_s.
  void order(StrikeOrder kind, double now_s, uint32_t target_id, vec3 target_head_m);
  FighterDecision think(const FighterSenses& senses);
  /// The strike decided by think() has played out.
  void strike_finished(double now_s);

  FighterPhase phase() const { return phase_; }
  const FighterBrainConfig& config() const { return config_; }
  void set_auto_attack(bool on) { config_.auto_attack = on; }

 private:
  FighterDecision strike(StrikeOrder kind, uint32_t target_id, vec3 head_m);

  FighterBrainConfig config_;
  FighterPhase phase_ = FighterPhase::kRest;
  StrikeOrder pending_ = StrikeOrder::kNone;
  double pending_since_s_ = 0;
  uint32_t pending_target_ = 0;
  vec3 pending_head_m_{0.0f};
  double ready_at_s_ = 0;  ///< End of the cool-down.
};

}  // namespace foresight::server

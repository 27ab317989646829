#include "fighters/fighter_brain.hpp"

namespace foresight::server {

void FighterBrain::order(StrikeOrder kind, double now_s, uint32_t target_id, vec3 target_head_m) {
  if (phase_ == FighterPhase::kStrike || kind == StrikeOrder::kNone) return;
  pending_ = kind;
  pending_since_s_ = now_s;
  pending_target_ = target_id;
  pending_head_m_ = target_head_m;
}

FighterDecision FighterBrain::think(const FighterSenses& s) {
  FighterDecision d;
  if (phase_ == FighterPhase::kStrike) return d;  // committed: stand and let it play
  if (pending_ != StrikeOrder::kNone && s.now_s - pending_since_s_ > config_.order_timeout_s)
    pending_ = StrikeOrder::kNone;
  if (phase_ == FighterPhase::kRecover && s.now_s >= ready_at_s_) phase_ = FighterPhase::kRest;
  if (!s.has_target) {
    if (phase_ != FighterPhase::kRecover) phase_ = FighterPhase::kRest;
    return d;
  }

  const vec2 to_target = s.target_pos_m - s.self_pos_m;
  const float distance = glm::length(to_target);
  const bool in_reach = distance <= config_.reach_m;
  // Hysteresis: once standing within reach, it follows again only past reach + slack, so a
  // target swaying at the edge does not make it start and stop every step.
  const bool was_following = phase_ == FighterPhase::kFollow;
  const bool far = distance > config_.reach_m + (was_following ? 0.0f : config_.follow_slack_m);
  const vec2 to_way = s.way_m - s.self_pos_m;
  if (far && glm::length(to_way) > 1e-4f) d.move_world = glm::normalize(to_way);
  if (phase_ != FighterPhase::kRecover) phase_ = far ? FighterPhase::kFollow : FighterPhase::kRest;

  // An order aims at the head where it was when ordered; the own policy at the head now.
  if (pending_ != StrikeOrder::kNone) {
    const float to_point = glm::length(vec2(pending_head_m_.x, pending_head_m_.z) - s.self_pos_m);
    if (to_point <= config_.reach_m + config_.follow_slack_m && s.can_strike) {
      d = strike(pending_, pending_target_, pending_head_m_);
      pending_ = StrikeOrder::kNone;
    }
  } else if (config_.auto_attack && phase_ != FighterPhase::kRecover && in_reach && s.can_strike) {
    d = strike(StrikeOrder::kAny, s.target_id, s.target_head_m);
  }
  return d;
}

FighterDecision FighterBrain::strike(StrikeOrder kind, uint32_t target_id, vec3 head_m) {
  phase_ = FighterPhase::kStrike;
  FighterDecision d;  // standing: no move
  d.strike = true;
  d.kind = kind;
  d.target_id = target_id;
  d.target_head_m = head_m;
  return d;
}

void FighterBrain::strike_finished(double now_s) {
  phase_ = FighterPhase::kRecover;
  ready_at_s_ = now_s + config_.cooldown_s;
}

}  // namespace foresight::server

#include "bot_brain.hpp"

#include "lookahead/scene_path.hpp"

#include <cmath>
#include <limits>
#include <string>

namespace foresight::bots {

namespace {

/// Further than a walking avatar moves in one frame: the server placed it anew.
constexpr float kTeleport_m = 3.0f;
constexpr double kPlanRetry_s = 1.0;
constexpr float kFreePointRadius_m = 0.75f;
constexpr float kWanderMin_m = 3.0f, kWanderMax_m = 10.0f;

float distance(vec2 a, vec2 b) { return glm::length(a - b); }

}  // namespace

void BotBrain::reset(BotScript script, uint64_t seed, double frame_interval_s) {
  script_ = script;
  rng_.seed(seed);
  player_ = ScriptedPlayer();
  player_config_ = ScriptedPlayerConfig();
  player_config_.frame_interval_s = frame_interval_s;
  has_target_ = false;
  target_goal_ = -1;
  next_plan_s_ = 0;
  has_last_pos_ = false;
  camera_yaw_rad_ = 0;
  replay_loop_ = -1;
  replay_reached_ = false;
  dodge_left_ = (rng_() & 1u) != 0;
}

ControlInput BotBrain::frame(const BotWorld& world, const BotFleetConfig& config, double t_s,
                             const Placement* own, const Threat* threat, int& plans_left) {
  if (own != nullptr) {
    const float moved = has_last_pos_ ? distance(own->pos_m, last_pos_) : 0.0f;
    if (moved > kTeleport_m) {
      has_target_ = false;  // respawned: the plan no longer fits
    } else {
      walked_m_ += moved;
    }
    has_last_pos_ = true;
    last_pos_ = own->pos_m;
  }
  if (!world.loaded) return waiting();
  if (script_ == BotScript::kReplay) {
    return replay(world, t_s, own ? own->pos_m : vec2(std::numeric_limits<float>::quiet_NaN()));
  }
  if (own == nullptr) return waiting();
  if (script_ == BotScript::kDodge && threat != nullptr) {
    const vec2 away = own->pos_m - threat->pos_m;
    const float d = glm::length(away);
    const float radius = config.dodge_radius_m * (threat->striking ? 2.0f : 1.0f);
    if (d < radius && d > 1e-3f) {
      ++dodge_frames_;
      has_target_ = false;  // a fresh wander target once safe
      // Away and to the side (the side kept per bot), as the camera behind at yaw 0 reads it.
      const vec2 out = away / d;
      const vec2 side(-out.y, out.x);
      const vec2 run = glm::normalize(out + (dodge_left_ ? 0.7f : -0.7f) * side);
      ControlInput in;
      in.camera_dir = vec2(-run.x, run.y);  // control_world_direction at yaw 0: right is -X
      camera_yaw_rad_ = 0.0f;
      return in;
    }
  }
  return steer(world, config, t_s, *own, plans_left);
}

ControlInput BotBrain::steer(const BotWorld& world, const BotFleetConfig& config, double t_s,
                             const Placement& own, int& plans_left) {
  const vec2 pos = own.pos_m;

  if (has_target_ && distance(pos, target_) <= target_radius_m_) {
    if (target_counts_) ++targets_reached_;
    has_target_ = false;
  }
  if (has_target_ && t_s - target_since_s_ > config.give_up_target_s) {
    ++targets_given_up_;
    has_target_ = false;
  }
  if (!has_target_) {
    if (t_s < next_plan_s_ || plans_left <= 0) return waiting();
    --plans_left;
    next_plan_s_ = t_s + kPlanRetry_s;  // the next try, should this one fail
    if (!pick_target(world, pos)) {
      ++plan_failures_;
      last_plan_failure_ = "no goal or free point to walk to near " + std::to_string(pos.x) + ", " + std::to_string(pos.y);
      return waiting();
    }
    player_config_.seed = rng_();
    // Counted, kept for the report (the fleet prints the distinct reasons) and retried.
    if (!player_.plan(*world.library, world.scene, world.world, own, target_, player_config_, last_plan_failure_)) {
      ++plan_failures_;
      return waiting();
    }
    has_target_ = true;
    target_since_s_ = t_s;
  }
  const ControlInput input = player_.frame(t_s, pos);
  camera_yaw_rad_ = input.camera_yaw_rad;
  return input;
}

bool BotBrain::pick_target(const BotWorld& world, vec2 pos) {
  const auto& goals = world.scene.goals;
  if (script_ == BotScript::kWander || script_ == BotScript::kDodge || goals.empty())
    return pick_free_point(world, pos);
  // Any goal but the one we stand in (counted without a vector: no allocation).
  int candidates = 0;
  for (const GoalPoint& g : goals) candidates += distance(pos, g.pos_m) > g.radius_m ? 1 : 0;
  if (candidates == 0) return pick_free_point(world, pos);
  int pick = static_cast<int>(unit() * candidates);
  for (size_t i = 0; i < goals.size(); ++i) {
    if (distance(pos, goals[i].pos_m) <= goals[i].radius_m) continue;
    if (pick-- == 0) {
      target_ = goals[i].pos_m;
      target_radius_m_ = goals[i].radius_m;
      target_goal_ = static_cast<int>(i);
      target_counts_ = true;
      return true;
    }
  }
  return false;
}

bool BotBrain::pick_free_point(const BotWorld& world, vec2 pos) {
  const GroundRect& bounds = world.scene.bounds;
  for (int attempt = 0; attempt < 12; ++attempt) {
    const float angle = static_cast<float>(unit()) * kTwoPi;
    const float radius = kWanderMin_m + static_cast<float>(unit()) * (kWanderMax_m - kWanderMin_m);
    const vec2 p = pos + radius * vec2(std::sin(angle), std::cos(angle));
    if (!bounds.contains(p)) continue;
    // Free for the library's own walker, so plan() has a chance.
    if (!scene_segment_clear(world.world, p, p, world.body_clearance_m, world.body_height_m)) {
      continue;
    }
    target_ = p;
    target_radius_m_ = kFreePointRadius_m;
    target_goal_ = -1;
    target_counts_ = script_ == BotScript::kWander || script_ == BotScript::kDodge;
    return true;
  }
  return false;
}

ControlInput BotBrain::replay(const BotWorld& world, double t_s, vec2 pos) {
  const Recording& rec = world.recording;
  const double period = rec.duration_s() + 1.0;
  const auto loop = static_cast<int64_t>(std::floor(t_s / period));
  const double local = t_s - static_cast<double>(loop) * period;
  if (loop != replay_loop_) {
    replay_loop_ = loop;
    replay_reached_ = false;
  }
  if (!replay_reached_ && std::isfinite(pos.x) && distance(pos, rec.goal_pos_m) <= rec.goal_radius_m) {
    ++targets_reached_;
    replay_reached_ = true;
  }
  if (local > rec.duration_s()) return waiting();
  const ControlInput input = recording_input_at(rec, local);
  camera_yaw_rad_ = input.camera_yaw_rad;
  return input;
}

ControlInput BotBrain::waiting() const {
  ControlInput stop;
  stop.camera_yaw_rad = camera_yaw_rad_;
  return stop;
}

}  // namespace foresight::bots

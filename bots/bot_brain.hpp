#pragma once
// One bot's script: what it holds on the keys each frame, from where its avatar is.
//   goals   a ScriptedPlayer (scripted/scripted_player.hpp: reaction delays, hesitation,
//           wrong taps, wiggles) steers from the avatar's position to a scene goal point picked at
//           random; within the goal's radius it counts and picks another goal (with a single
//           goal: a free point elsewhere first, uncounted, then the goal again).
//   wander  the same player, to random free points 3-10 m away.
//   dodge   wanders like `wander`, but an NPC fighter within dodge_radius (or striking within
//           twice that) makes it run: away from the fighter and to one side, so it leaves the
//           line of the strike; the look-ahead keeps the run clear of walls.
//   replay  the scene's evaluation recording, sample-and-hold from the Accept on, open loop (the
//           server's spawn is not the recording's, so it rarely ends at the recording's goal;
//           counted when it does). It repeats, one second after it ends.
// A target not reached within give_up_target_s is replaced; an avatar that jumps more than 3 m
// between two frames (respawned) gets a new plan. Plans (A* over the scene) are the only
// allocation, rationed per frame over all bots by the caller's plan budget.
#include "bot_config.hpp"
#include "bot_world.hpp"
#include "world/control_input.hpp"
#include "scripted/scripted_player.hpp"

#include <cstdint>
#include <random>
#include <string>

namespace foresight::bots {

/// The nearest NPC fighter as the snapshots show it.
struct Threat {
  vec2 pos_m{0.0f};
  bool striking = false;
};

class BotBrain {
 public:
  /// A fresh script (call on every Accept). `seed` is this bot's own.
  void reset(BotScript script, uint64_t seed, double frame_interval_s);

  /// The input to hold at t_s (seconds since Accept), seeing the avatar's root at `own` (nullptr:
  /// not seen yet) and the nearest fighter at `threat` (nullptr: none). `plans_left` is
  /// decremented for each route planned.
  ControlInput frame(const BotWorld& world, const BotFleetConfig& config, double t_s,
                     const Placement* own, const Threat* threat, int& plans_left);

  uint64_t targets_reached() const { return targets_reached_; }
  uint64_t plan_failures() const { return plan_failures_; }
  /// Why the last plan failed (empty when none has): the scripted player's reason, or that no
  /// free point or goal was left to pick.
  const std::string& last_plan_failure() const { return last_plan_failure_; }
  uint64_t targets_given_up() const { return targets_given_up_; }
  /// Frames spent running from a fighter (dodge).
  uint64_t dodge_frames() const { return dodge_frames_; }
  /// Path length of the avatar's root as seen frame to frame (jumps over 3 m excluded).
  double walked_m() const { return walked_m_; }

 private:
  ControlInput steer(const BotWorld& world, const BotFleetConfig& config, double t_s,
                     const Placement& own, int& plans_left);
  ControlInput replay(const BotWorld& world, double t_s, vec2 pos);
  bool pick_target(const BotWorld& world, vec2 pos);
  bool pick_free_point(const BotWorld& world, vec2 pos);
  ControlInput waiting() const;
  double unit() { return static_cast<double>(rng_() >> 11) * 0x1.0p-53; }

  BotScript script_ = BotScript::kGoals;
  std::mt19937_64 rng_;
  ScriptedPlayer player_;
  ScriptedPlayerConfig player_config_;
  bool has_target_ = false;
  vec2 target_{0.0f};
  float target_radius_m_ = 0.75f;
  bool target_counts_ = false;
  int target_goal_ = -1;  ///< Scene goal index, -1 for a free point.
  double target_since_s_ = 0;
  double next_plan_s_ = 0;
  bool has_last_pos_ = false;
  vec2 last_pos_{0.0f};
  float camera_yaw_rad_ = 0;  ///< Kept while waiting, so a stop is a stop and nothing else.
  int64_t replay_loop_ = -1;
  bool replay_reached_ = false;
  bool dodge_left_ = false;  ///< Which side a dodge runs to.
  uint64_t targets_reached_ = 0, plan_failures_ = 0, targets_given_up_ = 0, dodge_frames_ = 0;
  double walked_m_ = 0;
  std::string last_plan_failure_;
};

}  // namespace foresight::bots

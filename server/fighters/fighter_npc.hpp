#pragma once
// An NPC fighter's own state beside its avatar: its brain, its morphology, and the strike it is
// playing. Its avatar walks with the same look-ahead as a player's (so it never walks into a wall
// or another avatar); the brain steers it like a player's keys would.
#include "fighters/fighter_brain.hpp"
#include "fighters/fighter_motion.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace foresight::server {

struct FighterNpc {
  FighterNpc(const FighterBrainConfig& config, int morphology_index, std::string spawn_name)
      : brain(config), morphology(morphology_index), name(std::move(spawn_name)) {}

  FighterBrain brain;
  int morphology = 0;  ///< Index into default_morphologies().
  std::string name;    ///< The scene's NPC spawn name.
  uint32_t target_id = 0;  ///< Avatar it follows (0: none).
  /// The route around walls to the target (scene_route for the library's walker), replanned
  /// when the target has moved a metre or a second has passed; empty while the way is straight.
  std::vector<vec2> route;
  vec2 route_goal_m{0.0f};
  double route_at_s = -1e9;
  FighterMotion motion;
  // The strike playing (valid while motion.striking()).
  StrikeOrder strike_kind = StrikeOrder::kNone;
  uint32_t strike_target = 0;
  vec3 strike_target_head_m{0.0f};  ///< Stored when the strike was decided.
};

/// A strike's outcome, judged at its hit frame: did the effector come within the hit radius of
/// the target's head as it is now (not as it was when the strike was decided)?
struct StrikeEvent {
  uint32_t sequence = 0;  ///< 1, 2, ... per server.
  uint32_t tick = 0;
  uint32_t fighter = 0;   ///< Avatar ids.
  uint32_t target = 0;
  bool kick = false;
  bool hit = false;
  vec3 effector_m{0.0f};
  float miss_m = 0.0f;    ///< Effector to head at the hit frame.
  float reach_error_m = 0.0f;  ///< Effector to the stored target (what the adaptation could not bend).
};

}  // namespace foresight::server

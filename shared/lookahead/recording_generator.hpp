#pragma once
// Recordings without a person at the keyboard: a scripted "human" steers the real avatar (a
// LookaheadAvatar, strategy kCommand, a fixed expansion budget per 30 fps frame) from a spawn to a
// goal by looking at the avatar and pressing arrow keys, and what it pressed is the recording.
//
// Each display frame the player
//  * takes the camera the scene assigns to the avatar's root (the first camera whose region covers
//    it; the current one while it still covers; the last one when none does),
//  * follows a coarse route (scene_path.hpp) planned with the lowest body the library can move in
//    (so crouch-only passages are on the route; the avatar is never told to crouch): it heads for
//    the furthest point of the route, up to look_ahead_m ahead of the avatar's closest point on
//    it, that a clear straight line from the avatar reaches (waypoints within waypoint_reached_m
//    count as passed),
//  * turns that world direction into camera space and quantises it to the 8 arrow-key
//    directions, and
//  * behaves like a person, from a seeded std::mt19937_64: a reaction delay before following a
//    needed key change, a longer one now and then after a turn (late correction / overshoot),
//    occasional hesitation (all keys released for a moment), brief taps of a wrong key, and a
//    wiggle of the keys when the avatar has made no progress for a while.
// A sample is recorded only when the input or the camera changes (and at t = 0), stamped with the
// frame time rounded down to the millisecond, and a final "stop" sample follows the frame the goal
// is reached. Deterministic: the same library, scene and config give the same recording, byte for
// byte, and replay_recording with config.replay reproduces the generator's run exactly.
#include "lookahead/recording.hpp"
#include "lookahead/replay.hpp"
#include "world/scene.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace foresight {

struct HumanModel {
  double reaction_min_s = 0.15;  ///< Delay before following a needed key change: uniform in
  double reaction_max_s = 0.30;  ///< [min, max].
  double overshoot_probability = 0.35;  ///< After a turn (waypoint passed), the next change is
  double overshoot_min_s = 0.15;        ///< late by a further uniform [min, max].
  double overshoot_max_s = 0.45;
  double hesitations_per_min = 4;  ///< Rate of releasing every key ...
  double hesitation_min_s = 0.3;   ///< ... for uniform [min, max].
  double hesitation_max_s = 0.8;
  double wrong_taps_per_min = 3;  ///< Rate of pressing a neighbouring wrong key ...
  double wrong_tap_min_s = 0.1;   ///< ... for uniform [min, max].
  double wrong_tap_max_s = 0.25;
  double stuck_after_s = 4.0;  ///< No 0.3 m of progress for this long while pressing: wiggle
  double wiggle_s = 1.5;       ///< a key 45 or 90 deg off for this long.
};

struct RecordingGeneratorConfig {
  std::string scene;  ///< Written into Recording::scene (the name replays load).
  std::string name;   ///< Recording::name.
  std::string spawn;  ///< Spawn point name; empty: the scene's first.
  std::string goal;   ///< Goal point name; empty: the scene's first.
  uint64_t seed = 1;
  /// The avatar the player steers. Its expansion budget is what the recording was made with;
  /// wall_clock_spare_s is ignored (a deadline would not be deterministic) and max_seconds is
  /// the time cap of the recording.
  ReplayConfig replay;
  float route_clearance_m = 0.9f;   ///< Radius of the walker the route is planned for.
  float waypoint_reached_m = 0.8f;  ///< A waypoint this close counts as passed.
  float look_ahead_m = 4.0f;        ///< How far along the route the player looks.
  float sight_clearance_m = 0.5f;   ///< Width (radius) of the clear line it steers along.
  HumanModel human;
};

struct GeneratedRecording {
  Recording recording;
  bool reached_goal = false;
  std::vector<vec2> route;  ///< The planned waypoints, spawn first, goal last.
  float route_length_m = 0;
  float route_body_height_m = 0;  ///< The body height the route was planned for.
  ReplayResult run;               ///< The generator's own run of the avatar.
};

/// Plans the route and plays the scripted player until the goal or the time cap. False with a
/// reason when a spawn / goal name is unknown, the scene has no goal, there is no route, or the
/// avatar cannot start there. Not reaching the goal is not an error (see reached_goal).
bool recording_generate(const MotionLibrary& library, const Scene& scene, const CollisionWorld& world,
                        const RecordingGeneratorConfig& config, GeneratedRecording& out,
                        std::string& error);

/// The lowest body the library moves in: the minimum over locomotion segments of the highest
/// point of their collision volumes (crouch-walking for the default library). 1.85 m when the
/// library has no locomotion.
float lowest_moving_body_m(const MotionLibrary& library);

}  // namespace foresight

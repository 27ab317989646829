#pragma once
// Recordings without a person at the keyboard: a ScriptedPlayer (scripted_player.hpp: route,
// pure-pursuit steering, 8 arrow keys, reaction delays, hesitations, wrong taps, wiggles) steers
// the real avatar (a LookaheadAvatar through ReplayRun, strategy kCommand, a fixed expansion
// budget per 30 fps frame) from a spawn to a goal, and what it pressed is the recording. The
// same player drives the network bots (bots/): it needs nothing but the avatar's root position
// per frame, which a bot gets from the server as the generator gets it from its local avatar.
//
// Each display frame: the player gets the avatar's root and returns the input (arrow keys in
// camera space and the camera's yaw), which is recorded and played (ReplayRun::frame).
// A sample is recorded only when the input or the camera changes (and at t = 0), stamped with the
// frame time rounded down to the millisecond, and a final "stop" sample follows the frame the goal
// is reached. Deterministic: the same library, scene and config give the same recording, byte for
// byte, and replay_recording with config.replay reproduces the generator's run exactly.
#include "scripted/recording.hpp"
#include "scripted/replay.hpp"
#include "scripted/scripted_player.hpp"
#include "world/scene.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace foresight {

struct RecordingGeneratorConfig {
  std::string scene;  ///< Written into Recording::scene (the name replays load).
  std::string name;   ///< Recording::name.
  std::string spawn;  ///< Spawn point name; empty: the scene's first.
  std::string goal;   ///< Goal point name; empty: the scene's first.
  uint64_t seed = ScriptedPlayerConfig{}.seed;
  /// The avatar the player steers. Its expansion budget is what the recording was made with;
  /// wall_clock_spare_s is ignored (a deadline would not be deterministic), max_seconds is the
  /// time cap of the recording and frame_interval_s the player's frame interval.
  ReplayConfig replay;
  // The player: see ScriptedPlayerConfig (the defaults are its defaults).
  float route_clearance_m = ScriptedPlayerConfig{}.route_clearance_m;
  float waypoint_reached_m = ScriptedPlayerConfig{}.waypoint_reached_m;
  float look_ahead_m = ScriptedPlayerConfig{}.look_ahead_m;
  float sight_clearance_m = ScriptedPlayerConfig{}.sight_clearance_m;
  HumanModel human;

  /// The player's part (with frame_interval_s from replay).
  ScriptedPlayerConfig player_config() const {
    ScriptedPlayerConfig c;
    c.route_clearance_m = route_clearance_m;
    c.waypoint_reached_m = waypoint_reached_m;
    c.look_ahead_m = look_ahead_m;
    c.sight_clearance_m = sight_clearance_m;
    c.human = human;
    c.seed = seed;
    c.frame_interval_s = replay.frame_interval_s;
    return c;
  }
};

struct GeneratedRecording {
  Recording recording;
  bool reached_goal = false;
  std::vector<vec2> route;  ///< The planned waypoints, spawn first, goal last.
  float route_length_m = 0;
  float route_body_height_m = 0;  ///< The body height the route was planned for.
  ReplayResult run;               ///< The generator's own run of the avatar.
};

/// Plans the route (ScriptedPlayer::plan) and plays the scripted player until the goal or the
/// time cap. False with a reason when a spawn / goal name is unknown, the scene has no goal, the
/// player's config is not usable, there is no route, or the avatar cannot start there. Not
/// reaching the goal is not an error (see reached_goal).
bool recording_generate(const MotionLibrary& library, const Scene& scene, const CollisionWorld& world,
                        const RecordingGeneratorConfig& config, GeneratedRecording& out,
                        std::string& error);

}  // namespace foresight

#pragma once
// What every bot of a process shares, read-only once loaded: the motion library (the server
// checks its hash at connect), the scene the server named in its Accept with its collision world,
// and for the replay script the scene's evaluation recording. Loaded once, on the first Accept.
#include "bot_config.hpp"
#include "library/motion_library.hpp"
#include "scripted/recording.hpp"
#include "world/collision_world.hpp"
#include "world/scene.hpp"

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace foresight::bots {

struct BotWorld {
  const MotionLibrary* library = nullptr;
  bool loaded = false;
  Scene scene;
  CollisionWorld world;
  std::string scene_name;  ///< As the server named it in Accept.
  Recording recording;     ///< kReplay only.
  float body_height_m = 0; ///< lowest_moving_body_m(library): where routes must be free.
  float body_clearance_m = 0;  ///< moving_body_clearance_m(library): how wide they must be.
};

/// data/recordings/<scene>_eval.json
std::filesystem::path bot_recording_path(const std::string& scene_name);

/// Parses the scene file's `text` (the server's scene, own or fetched) with its collision world
/// and, for kReplay, loads its recording. False with a reason.
bool bot_world_load(BotWorld& out, const MotionLibrary& library, const std::string& scene_name,
                    std::string_view text, BotScript script, std::string& error);

}  // namespace foresight::bots

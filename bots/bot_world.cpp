#include "bot_world.hpp"

#include "scripted/scripted_player.hpp"
#include "world/data_paths.hpp"
#include "world/scene_load.hpp"

namespace foresight::bots {

std::filesystem::path bot_recording_path(const std::string& scene_name) {
  return data_dir() / "recordings" / (scene_name + "_eval.json");
}

bool bot_world_load(BotWorld& out, const MotionLibrary& library, const std::string& scene_name,
                    std::string_view text, BotScript script, std::string& error) {
  out.library = &library;
  out.loaded = false;
  out.scene_name = scene_name;
  if (!scene_parse(text, scene_name, out.scene, error) || !collision_world_build(out.scene, out.world, error)) {
    error = "cannot load the server's scene '" + scene_name + "': " + error;
    return false;
  }
  if (script == BotScript::kReplay) {
    const std::filesystem::path path = bot_recording_path(scene_name);
    if (!recording_load(path, out.recording, error)) {
      error = "replay needs " + path.string() + ": " + error;
      return false;
    }
    if (out.recording.samples.empty()) {
      error = "replay: " + path.string() + " has no samples";
      return false;
    }
  }
  out.body_height_m = lowest_moving_body_m(library);
  out.body_clearance_m = moving_body_clearance_m(library);
  out.loaded = true;
  return true;
}

}  // namespace foresight::bots

#include "world/data_paths.hpp"

#include "world/scene_load.hpp"

#include <cstdlib>

namespace foresight {

std::filesystem::path data_dir() {
  if (const char* env = std::getenv("FORESIGHT_DATA"); env && *env) return env;
  return FORESIGHT_DATA_DIR;
}

std::filesystem::path scene_path(std::string_view name_or_path) {
  const bool is_path = name_or_path.find('/') != std::string_view::npos ||
                       (name_or_path.size() > 5 && name_or_path.substr(name_or_path.size() - 5) == ".json");
  if (is_path) return std::filesystem::path(name_or_path);
  return data_dir() / "scenes" / (std::string(name_or_path) + ".json");
}

bool scene_world_load(std::string_view name_or_path, Scene& scene, CollisionWorld& world,
                      std::string& error) {
  return scene_load(scene_path(name_or_path), scene, error) &&
         collision_world_build(scene, world, error);
}

}  // namespace foresight

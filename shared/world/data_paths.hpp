#pragma once
// Where built-in data (scenes, recordings) is found: $FORESIGHT_DATA if set, else the repository's
// data/ folder as configured at build time.
#include "world/collision_world.hpp"
#include "world/scene.hpp"

#include <filesystem>
#include <string>
#include <string_view>

namespace foresight {

std::filesystem::path data_dir();

/// A built-in scene name ("maze") becomes data/scenes/maze.json; anything containing a '/' or
/// ending in ".json" is taken as a path as it is.
std::filesystem::path scene_path(std::string_view name_or_path);

/// scene_load(scene_path(name_or_path)) then collision_world_build: what every program that
/// moves avatars in a scene needs. False with the loader's or the builder's error.
bool scene_world_load(std::string_view name_or_path, Scene& scene, CollisionWorld& world,
                      std::string& error);

}  // namespace foresight

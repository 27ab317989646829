#pragma once
// Where built-in data (scenes, recordings) is found: $FORESIGHT_DATA if set, else the repository's
// data/ folder as configured at build time.
#include <filesystem>
#include <string_view>

namespace foresight {

std::filesystem::path data_dir();

/// A built-in scene name ("maze") becomes data/scenes/maze.json; anything containing a '/' or
/// ending in ".json" is taken as a path as it is.
std::filesystem::path scene_path(std::string_view name_or_path);

}  // namespace foresight

#pragma once
// Loading and validating scene files (format: docs/SCENES.md).
//
// Contract: these functions never throw and never crash on bad input. On failure they return
// false, leave `scene` untouched and set `error` to "<source>: <json.path>: <reason>", e.g.
//   maze.json: boxes[3].max: max.y (0.2) must be > min.y (0.5)
// and for malformed JSON "<source>: invalid JSON at line L, column C: <parser message>".
#include "world/scene.hpp"

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace foresight {

/// Largest scene file read.
inline constexpr std::uintmax_t kMaxSceneFileBytes = 512ull << 20;

/// Reads and parses a scene file; the error's source is the file name (no directories).
bool scene_load(const std::filesystem::path& path, Scene& scene, std::string& error);

/// Parses and validates scene JSON text. `source_name` prefixes error messages.
bool scene_parse(std::string_view json_text, std::string_view source_name, Scene& scene,
                 std::string& error);

/// The semantic checks scene_parse runs after reading the fields, for scenes built in code:
/// caps, bounds size, spawns/goals/NPCs inside the bounds, on ground and not inside a box,
/// cameras whose region meets the bounds. Does not re-check per-field ranges that only a parse
/// can get wrong (NaN, min >= max are checked too, cheaply).
bool scene_validate(const Scene& scene, std::string_view source_name, std::string& error);

}  // namespace foresight

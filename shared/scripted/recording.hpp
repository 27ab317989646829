#pragma once
// A recorded navigation task (paper 5.1): the player's commands over time, so that the same input
// can be replayed against every exploration strategy. Format: docs/RECORDINGS.md.
//
// Contract: parsing and loading never throw and never crash on bad input. On failure they return
// false, leave the output untouched and set `error` to "<source>: <json.path>: <reason>", e.g.
//   maze_train.json: samples[12].t: 3.2 is not after the previous sample's t (3.2)
// A parsed recording is valid: finite numbers, |dir| <= 1, timestamps strictly increasing from 0.
#include "world/control_input.hpp"
#include "math/types.hpp"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace foresight {

/// The input from time t_s on (held until the next sample).
struct CommandSample {
  double t_s = 0;
  ControlInput input;
  vec3 camera_pos_m{0.0f};  ///< Where the camera was (drawing and debugging only).
};

struct Recording {
  std::string scene;  ///< Built-in scene name or path, as data_paths.hpp's scene_path() takes it.
  std::string name;
  vec2 start_pos_m{0.0f};  ///< Where the avatar spawns (ground x, z), in the idle segment.
  float start_heading_rad = 0;
  vec2 goal_pos_m{0.0f};
  float goal_radius_m = 0.75f;
  std::vector<CommandSample> samples;  ///< Strictly increasing t_s, the first at 0.
  /// MotionLibrary::content_hash of the library it was recorded with (0: unknown). Replays with
  /// another library are allowed; only the avatar's response, not the commands, depends on it.
  uint64_t library_hash = 0;

  /// Time of the last sample (0 when there is none).
  double duration_s() const { return samples.empty() ? 0.0 : samples.back().t_s; }
};

inline constexpr std::string_view kRecordingFormat = "foresight-recording";
inline constexpr int kRecordingVersion = 1;
// Caps against hostile or mistyped files (a 1,000,000-sample recording is ~9 hours at 30 fps).
inline constexpr std::size_t kMaxRecordingSamples = 1000000;
inline constexpr std::uintmax_t kMaxRecordingFileBytes = 256u << 20;
inline constexpr double kMaxRecordingTime_s = 1.0e6;
inline constexpr float kMaxRecordingCoord_m = 100000.0f;

/// Parses and validates recording JSON text. `source_name` prefixes error messages.
bool recording_parse(std::string_view json, std::string_view source_name, Recording& recording,
                     std::string& error);
/// Reads and parses a file; the error's source is the file name.
bool recording_load(const std::filesystem::path& path, Recording& recording, std::string& error);

/// The JSON text of a recording, one sample per line. Numbers are written in the shortest form
/// that parses back to the same float / double, so recording_parse(recording_write(r)) == r for
/// any valid r, and writing is deterministic.
std::string recording_write(const Recording& recording);
/// Writes the text to `path` (through a temporary file renamed over it). False with a reason on
/// I/O failure.
bool recording_save(const std::filesystem::path& path, const Recording& recording,
                    std::string& error);

/// Sample-and-hold: the input of the last sample with t_s <= t (binary search). Before the first
/// sample (or with no samples): stop (ControlInput{}).
ControlInput recording_input_at(const Recording& recording, double t_s);

}  // namespace foresight

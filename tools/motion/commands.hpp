#pragma once
// Subcommands of foresight-motion. Each returns the process exit code.
#include "library_build/library_source.hpp"
#include "scripted/replay.hpp"

#include <cstdint>
#include <string>

namespace foresight::tools {

struct PlayOptions {
  std::string scene = "maze";  ///< Built-in scene name or a path to a scene .json file.
  double seconds = 30.0;
  uint64_t seed = 1;
  int64_t expansions_per_frame = 200;  ///< Look-ahead budget per frame.
  bool verbose = false;  ///< Also print every frame's root placement.
};

struct SteerOptions {
  std::string recording;  ///< Recording .json (its scene is loaded).
  std::string strategy = "command";
  int64_t expansions_per_frame = ReplayConfig{}.expansions_per_frame;  // what recordings are made with
  double max_seconds = 300;
  /// Training recording for strategies 3 and 4 (empty: the scene's shipped <scene>_train.json,
  /// else the steered recording itself).
  std::string train;
};

int command_info(const MotionSource& source, bool brief, bool json);
int command_graph(const MotionSource& source);
int command_export_bvh(const MotionSource& source, const std::string& out_dir);
int command_play(const MotionSource& source, const PlayOptions& options);
int command_steer(const MotionSource& source, const SteerOptions& options);

/// Loads the library or prints why not (false).
bool load_library_or_report(const MotionSource& source, MotionLibrary& lib);

}  // namespace foresight::tools

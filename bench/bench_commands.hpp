#pragma once
// Subcommands of foresight-bench. Each prints the machine it ran on, its figures, and with `json`
// one JSON object as its last line. Returns the process exit code.
#include "library_build/library_source.hpp"

#include <string>
#include <vector>

namespace foresight::bench {

struct CollisionBenchOptions {
  std::string scene = "maze";
  double seconds = 3.0;
  unsigned long long seed = 1;
  std::string motions;  ///< Empty: the default library.
  bool json = false;
};
int bench_collision(const CollisionBenchOptions& options);

struct BvhBenchOptions {
  std::string file;  ///< Empty: the largest .bvh under ../shared/mocap.
  int runs = 20;
  bool json = false;
};
int bench_bvh(const BvhBenchOptions& options);

struct GraphBenchOptions {
  std::string motions;  ///< Folder of BVH clips.
  int runs = 3;
  bool json = false;
};
int bench_graph(const GraphBenchOptions& options);

struct LookaheadBenchOptions {
  std::string scene = "maze";
  std::string strategy = "command";
  double seconds = 3.0;
  int expansions_per_tree = 4000;  ///< Then the tree is reset at a new random placement.
  unsigned long long seed = 1;
  bool json = false;
};
int bench_lookahead(const LookaheadBenchOptions& options);

struct ClientBenchOptions {
  int avatars = 1000;
  double seconds = 3.0;
  unsigned long long seed = 1;
  bool json = false;
};
/// Only built when foresight_client is (FORESIGHT_HAVE_CLIENT).
int bench_client(const ClientBenchOptions& options);

struct FighterBenchOptions {
  int queries = 20000;         ///< Timed retrievals per database.
  unsigned long long seed = 1;
  std::string figure_dir;      ///< Non-empty: also write the adapted-strikes SVGs there.
  bool json = false;
};
int bench_fighter(const FighterBenchOptions& options);

struct MotionQualityBenchOptions {
  std::string scene = "maze";
  std::string goal;      ///< The scene's goal by name (default: its first).
  MotionSource motions;  ///< Default: the built-in library.
  int seeds = 10;
  double max_seconds = 120.0;
  /// Moves every step block of the scene this far along z (a level nobody tuned for: the feet
  /// meet the edges in another phase; docs/MOTION_QUALITY.md's stairs figures).
  float shift_steps_m = 0.0f;
  bool json = false;
};
int bench_motion_quality(const MotionQualityBenchOptions& options);

struct SnapshotBenchOptions {
  int avatars = 1000;    ///< In the world.
  int receivers = 200;   ///< Clients, each with its own view and history.
  int view = 50;         ///< Avatars in each view (the interest radius's 8 m at 1000 on the field).
  int snapshots = 200;   ///< Timed, after the warm-up.
  unsigned long long seed = 1;
  bool json = false;
};
int bench_snapshot(const SnapshotBenchOptions& options);

struct LoadReportOptions {
  std::vector<std::string> inputs;  ///< Files whose last JSON line is foresight-bots --json output.
  std::string out_dir = "out/loadtest";
};
int bench_load_report(const LoadReportOptions& options);

/// Median of a list of samples (the list is reordered).
double median(std::vector<double>& samples);

}  // namespace foresight::bench

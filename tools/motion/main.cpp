// foresight-motion: inspect, export and play motion libraries.
//   foresight-motion info  [--motions DIR] [--json] [--bvh-units U | --bvh-scale S] [--bvh-root R]
//   foresight-motion graph  --motions DIR [--threshold M]
//   foresight-motion export-bvh OUT_DIR [--motions DIR]
//   foresight-motion play [--scene maze] [--seconds 30] [--seed 1] [--motions DIR]
//   foresight-motion steer --recording FILE [--strategy command] [--expansions 300]
#include "commands.hpp"
#include "library_build/motion_source_cli.hpp"

#include <CLI/CLI.hpp>

#include <map>

int main(int argc, char** argv) {
  using namespace foresight;
  CLI::App app{"foresight-motion: inspect, export and play Foresight motion libraries"};
  app.require_subcommand(1);
  app.fallthrough();  // --motions and --threshold may follow the subcommand
  MotionSource source;
  add_motion_source_options(app, source);

  auto* info = app.add_subcommand("info", "Clips, segments, transitions and content hash");
  bool brief = false;
  info->add_flag("--brief", brief, "Only the one-line summary");
  bool info_json = false;
  info->add_flag("--json", info_json, "One JSON line: per clip what the import decided, and the library");
  auto* graph = app.add_subcommand("graph", "Build the automatic graph and report nodes/edges");
  std::string out_dir;
  auto* export_bvh = app.add_subcommand("export-bvh", "Write every clip as a BVH file");
  export_bvh->add_option("out_dir", out_dir, "Output folder")->required();
  tools::PlayOptions play_options;
  auto* play = app.add_subcommand(
      "play", "An avatar wanders (random held directions) with look-ahead in a scene, headless");
  play->add_option("--scene", play_options.scene, "Built-in scene name or scene .json path");
  play->add_option("--seconds", play_options.seconds, "Simulated seconds")->check(CLI::Range(0.0, 36000.0));
  play->add_option("--seed", play_options.seed, "Seed of the wandering directions");
  play->add_option("--expansions", play_options.expansions_per_frame,
                   "Look-ahead expansions per frame")->check(CLI::Range(0, 100000000));
  play->add_flag("--verbose", play_options.verbose, "Print every frame");

  tools::SteerOptions steer_options;
  auto* steer = app.add_subcommand(
      "steer", "Replay a recorded player steering an avatar with look-ahead, headless");
  steer->add_option("--recording", steer_options.recording, "Recording .json")
      ->required()
      ->check(CLI::ExistingFile);
  steer->add_option("--strategy", steer_options.strategy, "Exploration strategy (name or 0-4)");
  steer->add_option("--expansions", steer_options.expansions_per_frame,
                    "Look-ahead expansions per frame")->check(CLI::Range(0, 100000000));
  steer->add_option("--max-seconds", steer_options.max_seconds, "Give up after this long")
      ->check(CLI::Range(1.0, 36000.0));
  steer->add_option("--train", steer_options.train,
                    "Training recording for strategies statistic and hybrid (default: the scene's "
                    "<scene>_train.json, else the steered recording)")
      ->check(CLI::ExistingFile);

  CLI11_PARSE(app, argc, argv);
  if (*info) return tools::command_info(source, brief, info_json);
  if (*graph) return tools::command_graph(source);
  if (*export_bvh) return tools::command_export_bvh(source, out_dir);
  if (*steer) return tools::command_steer(source, steer_options);
  return tools::command_play(source, play_options);
}

// foresight-lab: the paper's Fig. 9 and Fig. 10 and the navigation comparison, replayed from the
// shipped recordings (docs/LAB.md).
//   foresight-lab --scene maze --out DIR [--json] [--quick] [--seeds 20] [--responsive-seeds 200]
//                 [--motions DIR]   (a captured library instead of the built-in one)
#include "bench_json.hpp"
#include "lab/lab_experiments.hpp"
#include "lab/lab_report.hpp"
#include "library_build/motion_source_cli.hpp"

#include <CLI/CLI.hpp>

#include <cstdio>

int main(int argc, char** argv) {
  using namespace foresight::lab;
  CLI::App app{"foresight-lab: the feasible-motion-tree paper's experiments (docs/LAB.md)"};
  LabOptions options;
  std::string out_dir;
  bool json = false;
  app.add_option("--scene", options.scene, "Scene with shipped recordings: maze or obstacles");
  app.add_option("--out", out_dir, "Folder for fig9.csv/.svg, fig10.csv/.svg, navigation.csv, responses.csv")
      ->required();
  app.add_flag("--json", json, "Print one JSON object with every figure as the last line");
  app.add_flag("--quick", options.quick, "Three frame intervals and one closed-loop seed (tests, CI)");
  app.add_option("--seeds", options.closed_loop_seeds, "Closed-loop player seeds 1..N per controller")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  app.add_option("--responsive-seeds", options.responsive_seeds,
                 "Closed-loop seeds for look-ahead 1 + steering (at least --seeds)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  app.add_option("--paper-rate", options.paper_expansions_per_s,
                 "Assumed expansions/s of the paper's machine")
      ->check(CLI::Range(1.0, 1e9));
  app.add_option("--nav-budget", options.navigation_expansions_per_frame,
                 "Expansions per 1/30 s frame in the navigation runs")
      ->check(CLI::Range(int64_t{0}, int64_t{1} << 30));
  double frame_cost_ms = 1000.0 * options.frame_cost_s;
  app.add_option("--frame-cost-ms", frame_cost_ms, "Fixed cost of a frame (rendering), ms")
      ->check(CLI::Range(0.0, 1000.0));
  foresight::MotionSource motions;
  foresight::add_motion_source_options(app, motions);
  CLI11_PARSE(app, argc, argv);
  options.frame_cost_s = frame_cost_ms / 1000.0;

  LabScene lab;
  std::string error;
  if (!lab_load(options.scene, motions, lab, error)) {
    std::fprintf(stderr, "foresight-lab: %s\n", error.c_str());
    return 1;
  }
  LabResult result = run_lab(lab, options);
  if (!result.error.empty()) {
    std::fprintf(stderr, "foresight-lab: %s\n", result.error.c_str());
    return 1;
  }
  if (!motions.motions_dir.empty()) {
    // The same closed loop on the built-in library, to print beside this one.
    LabScene builtin;
    if (!lab_load(options.scene, {}, builtin, error)) {
      std::fprintf(stderr, "foresight-lab: built-in library: %s\n", error.c_str());
      return 1;
    }
    result.builtin_closed_loop = run_closed_loop_navigation(builtin, options, lab_learn_statistics(builtin, options));
  }
  if (!lab_write_files(result, lab.scene, out_dir, error)) {
    std::fprintf(stderr, "foresight-lab: %s\n", error.c_str());
    return 1;
  }
  foresight::bench::print_machine_line();
  std::printf("scene %s: train '%s' (%.1f s), eval '%s' (%.1f s), library %s %016llx (%s)\n\n",
              lab.name.c_str(), lab.train.name.c_str(), lab.train.duration_s(),
              lab.eval.name.c_str(), lab.eval.duration_s(), lab.library.name.c_str(),
              static_cast<unsigned long long>(lab.library.content_hash),
              result.recordings_match_library ? "the recordings' library"
                                              : "NOT the library the recordings were made with");
  std::printf("%s\n%s\n%s\n%s\n", fig9_text(result.fig9).c_str(),
              fig10_text(result.fig10).c_str(), navigation_text(result.navigation).c_str(),
              navigation_text(result.closed_loop).c_str());
  if (result.builtin_closed_loop)
    std::printf("The same closed loop on the built-in library, for comparison:\n%s\n",
                navigation_text(*result.builtin_closed_loop).c_str());
  std::printf("Motion quality on the shown poses (docs/MOTION_QUALITY.md), closed loop, scene's first spawn to its first goal:\n%s\n",
              motion_quality_text(result.motion_quality).c_str());
  std::printf("wrote %s/{fig9.csv,fig9.svg,fig10.csv,fig10.svg,navigation.csv,responses.csv}\n", out_dir.c_str());
  std::printf("runtime %.1f s:", result.wall_s);
  for (const auto& [name, seconds] : result.phase_s) std::printf(" %s %.1f s", name.c_str(), seconds);
  std::printf("\n");
  if (json) std::printf("%s\n", lab_json(result).c_str());
  return 0;
}

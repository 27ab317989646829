// foresight-bench fighter: the NPC fighter's figures against the paper's (retrieval 0.28 s,
// adaptation 88 / 515 / 1240 us per frame on a 2006 PC): retrieval on a 75-entry and a 10,000-entry
// database (fighter_retrieval_bench), adaptation per frame, reach error and foot skate
// (fighter_adapt_bench); optionally the picture of one strike adapted on five morphologies.
#include "bench_commands.hpp"
#include "bench_json.hpp"
#include "fighter_adapt_bench.hpp"
#include "fighter_figure.hpp"
#include "fighter_retrieval_bench.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>

namespace foresight::bench {

int bench_fighter(const FighterBenchOptions& o) {
  print_machine_line();
  if (!o.figure_dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(o.figure_dir, ec);
    for (bool side : {true, false}) {
      FighterFigureOptions f;
      f.side_view = side;
      const std::filesystem::path path =
          std::filesystem::path(o.figure_dir) / (side ? "fighter-adaptation-side.svg" : "fighter-adaptation-front.svg");
      const std::string svg = fighter_adaptation_svg(f);
      if (svg.empty()) {
        std::fprintf(stderr, "foresight-bench fighter: cannot build the fighters' limb models\n");
        return 1;
      }
      std::ofstream out(path, std::ios::binary);
      out << svg;
      if (!out) {
        std::fprintf(stderr, "foresight-bench fighter: cannot write %s\n", path.string().c_str());
        return 1;
      }
      std::printf("wrote %s\n", path.string().c_str());
    }
  }

  FighterRetrievalBenchConfig rc;
  const std::filesystem::path mocap = std::filesystem::path(FORESIGHT_MOCAP_DIR) / "fighting";
  if (std::filesystem::is_directory(mocap)) {
    rc.mocap_fighting_dir = mocap;
    rc.sidecar = std::filesystem::path(FORESIGHT_DATA_DIR) / "fighter" / "bandai_fighting.strikes.json";
  }
  rc.queries = o.queries;
  rc.seed = o.seed;
  const FighterRetrievalBenchResult retrieval = run_fighter_retrieval_bench(rc);
  if (!retrieval.error.empty()) {
    std::fprintf(stderr, "foresight-bench fighter: %s\n", retrieval.error.c_str());
    return 1;
  }
  std::printf("%s", describe(retrieval).c_str());

  FighterAdaptBenchOptions ac;
  ac.seed = o.seed;
  const FighterAdaptBenchResult a = run_fighter_adapt_bench(ac);
  if (!a.error.empty()) {
    std::fprintf(stderr, "foresight-bench fighter: %s\n", a.error.c_str());
    return 1;
  }
  std::printf("adaptation: %d strikes, %d frames (%d limb / %d torso / %d far targets)\n", a.strikes, a.frames,
              a.limb_targets, a.torso_targets, a.far_targets);
  std::printf("  us per frame p50 %.1f p99 %.1f (limb alone p50 %.1f; with the torso p50 %.1f p99 %.1f)\n",
              a.adapt_us_per_frame_p50, a.adapt_us_per_frame_p99, a.limb_us_per_frame_p50,
              a.torso_us_per_frame_p50, a.torso_us_per_frame_p99);
  std::printf("  reach error cm p50 %.2f p99 %.2f (torso class p99 %.2f, %d of %d torso targets missed by > 1 cm)\n",
              a.reach_error_cm_p50, a.reach_error_cm_p99, a.reach_error_torso_cm_p99, a.torso_targets_missed,
              a.torso_targets);
  std::printf("  support foot skate %.3f cm/s (largest drift %.3f cm), %d frames with NaN/inf\n",
              a.foot_skate_cm_per_s, a.foot_drift_cm_max, a.non_finite);
  if (o.json) {
    // The retrieval figures, then the adaptation figures.
    Json j = to_json(retrieval);
    j["adapt_us_per_frame_p50"] = rounded(a.adapt_us_per_frame_p50, 3);
    j["adapt_us_per_frame_p99"] = rounded(a.adapt_us_per_frame_p99, 3);
    j["reach_error_cm_p50"] = rounded(a.reach_error_cm_p50, 3);
    j["reach_error_cm_p99"] = rounded(a.reach_error_cm_p99, 3);
    j["foot_skate_cm_per_s"] = rounded(a.foot_skate_cm_per_s, 4);
    j["adapt_frames"] = a.frames;
    j["adapt_non_finite"] = a.non_finite;
    print_json_line(std::move(j));
  }
  return a.non_finite == 0 ? 0 : 1;
}

}  // namespace foresight::bench

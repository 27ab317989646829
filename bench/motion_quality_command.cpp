// motion-quality: closed-loop players steer the paper's controller, steering without the pose
// stage and steering with it (the default), and every shown pose is measured (lab/motion_quality.hpp,
// docs/MOTION_QUALITY.md).
#include "bench_commands.hpp"
#include "bench_json.hpp"
#include "lab/lab_experiments.hpp"
#include "lab/motion_quality.hpp"
#include "library_build/library_source.hpp"
#include "world/data_paths.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <string>

namespace foresight::bench {
namespace {

const float kSteerRadPerS = radians(lab::kLabSteerDegPerS);  // the lab's responsive controller

}  // namespace

int bench_motion_quality(const MotionQualityBenchOptions& o) {
  MotionLibrary lib;
  Scene scene;
  CollisionWorld world;
  std::string error;
  if (!motion_library_load(o.motions, lib, error) || !scene_world_load(o.scene, scene, world, error)) {
    std::fprintf(stderr, "foresight-bench motion-quality: %s\n", error.c_str());
    return 1;
  }
  if (o.shift_steps_m != 0.0f && !lab::shift_steps(scene, world, o.shift_steps_m, error)) {
    std::fprintf(stderr, "foresight-bench motion-quality: --shift-steps: %s\n", error.c_str());
    return 1;
  }
  lab::MotionQualityOptions options;
  options.seeds = o.seeds;
  options.max_seconds = o.max_seconds;
  options.goal = o.goal;
  const std::vector<lab::MotionQualityResult> results =
      lab::measure_motion_quality(lib, scene, world, lab::motion_quality_controllers(kSteerRadPerS), options, error);
  if (results.empty()) {
    std::fprintf(stderr, "foresight-bench motion-quality: %s\n", error.c_str());
    return 1;
  }
  print_machine_line();
  std::printf("scene %s (goal %s, steps moved %.2f m), library %s, %d closed-loop player seeds per controller, "
              "pop threshold %.1f mm/frame^2\n",
              scene.name.c_str(), o.goal.empty() ? scene.goals.front().name.c_str() : o.goal.c_str(),
              static_cast<double>(o.shift_steps_m), lib.name.c_str(), o.seeds,
              1000.0 * results.front().pop_threshold_m);
  std::fputs(lab::motion_quality_text(results).c_str(), stdout);
  if (o.json) {
    // Top level: the default controller (steering with the pose stage, the last row); every row
    // under "controllers"; then where it ran.
    nlohmann::json j = {{"bench", "motion-quality"}, {"scene", scene.name}, {"goal", o.goal}, {"library", lib.name},
                        {"seeds", o.seeds},          {"controller", results.back().controller},
                        {"shift_steps_m", o.shift_steps_m}};
    j.update(lab::motion_quality_json(results.back()));
    for (const lab::MotionQualityResult& r : results) {
      nlohmann::json row = lab::motion_quality_json(r);
      row["name"] = r.controller;
      j["controllers"].push_back(row);
    }
    print_json_line(j);  // j's keys in their (alphabetical) order, then where it ran
  }
  return 0;
}

}  // namespace foresight::bench

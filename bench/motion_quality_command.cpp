// motion-quality: closed-loop players steer the paper's controller, steering without the pose
// stage and steering with it (the default), and every shown pose is measured (lab/motion_quality.hpp,
// docs/MOTION_QUALITY.md).
#include "bench_commands.hpp"
#include "lab/motion_quality.hpp"
#include "library/library_source.hpp"
#include "machine_info.hpp"
#include "world/data_paths.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <string>

namespace foresight::bench {
namespace {

constexpr float kSteerRadPerS = 9.424778f;  // 540 deg/s, the lab's responsive controller

nlohmann::json result_json(const lab::MotionQualityResult& r) {
  return {{"foot_skate_cm_per_s_p50", r.foot_skate_cm_per_s_p50}, {"foot_skate_cm_per_s_p95", r.foot_skate_cm_per_s_p95},
          {"foot_skate_cm_per_s_max", r.foot_skate_cm_per_s_max}, {"ground_error_cm_p95", r.ground_error_cm_p95},
          {"ground_error_cm_max", r.ground_error_cm_max},
          {"pops_per_min", r.pops_per_min},                       {"limit_violations", r.limit_violations},
          {"response_ms_p50", r.response_ms_p50},                 {"response_ms_p95", r.response_ms_p95},
          {"collisions", r.collisions},                           {"goals_reached_share", r.goals_reached_share}};
}

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
  std::printf("machine: %s\n", machine_description().c_str());
  std::printf("scene %s (goal %s), library %s, %d closed-loop player seeds per controller, pop threshold %.1f mm/frame^2\n",
              scene.name.c_str(), o.goal.empty() ? scene.goals.front().name.c_str() : o.goal.c_str(), lib.name.c_str(),
              o.seeds, 1000.0 * results.front().pop_threshold_m);
  std::printf("  %-40s %7s %22s %13s %8s %7s %12s %7s %9s\n", "controller", "goals", "skate cm/s p50/p95/max",
              "ground p95/max", "pops/min", "limits", "resp p50/p95", "collide", "inertial.");
  for (const lab::MotionQualityResult& r : results)
    std::printf("  %-40s %3d/%-3d %6.2f / %5.2f / %6.1f %5.2f / %5.1f %8.2f %7lld %5.0f / %5.0f %7lld %9lld\n",
                r.controller.c_str(), r.goals_reached, r.runs, r.foot_skate_cm_per_s_p50, r.foot_skate_cm_per_s_p95,
                r.foot_skate_cm_per_s_max, r.ground_error_cm_p95, r.ground_error_cm_max, r.pops_per_min,
                static_cast<long long>(r.limit_violations), r.response_ms_p50, r.response_ms_p95,
                static_cast<long long>(r.collisions), static_cast<long long>(r.discontinuities));
  for (const lab::MotionQualityResult& r : results)
    if (r.shown_collisions != r.played_collisions)
      std::printf("  %s: %lld shown frames collide, %lld played\n", r.controller.c_str(),
                  static_cast<long long>(r.shown_collisions), static_cast<long long>(r.played_collisions));
  if (o.json) {
    // Top level: the default controller (steering with the pose stage, the last row); every row
    // under "controllers"; then where it ran.
    nlohmann::json j = {{"bench", "motion-quality"}, {"scene", scene.name}, {"goal", o.goal}, {"library", lib.name},
                        {"seeds", o.seeds},          {"controller", results.back().controller}};
    j.update(result_json(results.back()));
    for (const lab::MotionQualityResult& r : results) {
      nlohmann::json row = result_json(r);
      row["name"] = r.controller;
      j["controllers"].push_back(row);
    }
    std::string text = j.dump();
    text.pop_back();  // reopen the object for the machine fields
    std::printf("%s,%s}\n", text.c_str(), machine_json_fields().c_str());
  }
  return 0;
}

}  // namespace foresight::bench

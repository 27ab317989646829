// collision: the default library's (or a BVH folder's) real segment shapes, placed at random in a
// scene, checked on one core.
#include "bench_commands.hpp"
#include "bench_json.hpp"
#include "collision_bench.hpp"
#include "library_build/library_source.hpp"
#include "world/collision_world.hpp"
#include "world/data_paths.hpp"
#include "world/scene_load.hpp"

#include <cstdio>

namespace foresight::bench {

int bench_collision(const CollisionBenchOptions& o) {
  MotionLibrary lib;
  Scene scene;
  CollisionWorld world;
  std::string error;
  if (!motion_library_load({o.motions, {}, {}}, lib, error) ||
      !scene_world_load(o.scene, scene, world, error)) {
    std::fprintf(stderr, "foresight-bench collision: %s\n", error.c_str());
    return 1;
  }
  const CollisionBenchResult r = run_collision_bench(world, lib.segment_shapes, o.seconds, o.seed);
  print_machine_line();
  std::printf("scene %s, library %s (%zu segment shapes), %.1f s on one thread\n",
              scene.name.c_str(), lib.name.c_str(), lib.segment_shapes.size(), r.seconds);
  std::printf("  %.1f M frame checks/s, %.2f M clip checks/s, %.1f frames tested per clip, "
              "%.0f%% feasible, %.0f%% decided by the whole-sweep test\n",
              r.frame_checks_per_sec / 1e6, r.clip_checks_per_sec / 1e6, r.frames_per_clip,
              100.0 * r.feasible_share, 100.0 * r.early_out_share);
  if (o.json) {
    Json j = to_json(r);
    j["bench"] = "collision";
    j["scene"] = scene.name;
    j["library"] = lib.name;
    print_json_line(std::move(j));
  }
  return 0;
}

}  // namespace foresight::bench

// lookahead: feasible motion trees grown from random free placements of random segments, with a
// random command, on one thread. One expansion = one successor placed, collision-checked over all
// its frames and prioritised (MotionTree::grow's count).
#include "bench_commands.hpp"
#include "bench_json.hpp"
#include "library_build/library_source.hpp"
#include "lookahead/motion_tree.hpp"
#include "world/data_paths.hpp"
#include "world/scene_load.hpp"

#include <chrono>
#include <cstdio>
#include <random>

namespace foresight::bench {

int bench_lookahead(const LookaheadBenchOptions& o) {
  MotionLibrary lib = motion_library_default();
  Scene scene;
  CollisionWorld world;
  std::string error;
  Strategy strategy;
  if (!strategy_parse(o.strategy, strategy, error) ||
      !scene_world_load(o.scene, scene, world, error)) {
    std::fprintf(stderr, "foresight-bench lookahead: %s\n", error.c_str());
    return 1;
  }
  // Roots: random segments at random placements where they are free (drawn before timing).
  struct Root {
    int segment;
    Placement start;
    vec2 command;
  };
  std::mt19937_64 rng(o.seed);
  std::uniform_real_distribution<float> ux(scene.bounds.min_m.x, scene.bounds.max_m.x);
  std::uniform_real_distribution<float> uz(scene.bounds.min_m.y, scene.bounds.max_m.y);
  std::uniform_real_distribution<float> angle(-kPi, kPi);
  std::uniform_int_distribution<int> segment(0, lib.graph.num_segments() - 1);
  std::vector<Root> roots;
  for (int tries = 0; roots.size() < 256 && tries < 1000000; ++tries) {
    const Root r{segment(rng), {vec2(ux(rng), uz(rng)), angle(rng)}, vec2(0.0f)};
    if (!segment_feasible(world, lib.segment_shapes[r.segment], r.start)) continue;
    const float a = angle(rng);
    roots.push_back({r.segment, r.start, vec2(std::sin(a), std::cos(a))});
  }
  if (roots.empty()) return std::fprintf(stderr, "no free placement found\n"), 1;

  MotionTreeConfig config;
  config.strategy = strategy;
  config.max_nodes = kMaxTreeNodes;
  MotionTree tree(lib, world, config);
  using Clock = std::chrono::steady_clock;
  int64_t expansions = 0, nodes = 0, frame_checks = 0, trees = 0;
  double size_sum = 0;
  const auto t0 = Clock::now();
  const auto end = t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(o.seconds));
  while (Clock::now() < end) {
    const Root& r = roots[static_cast<size_t>(trees) % roots.size()];
    tree.reset(r.segment, r.start);
    tree.set_command(r.command, r.start);
    const GrowResult g = tree.grow(GrowBudget::expansions(o.expansions_per_tree));
    expansions += g.expansions;
    nodes += g.nodes_added;
    frame_checks += g.frame_checks;
    size_sum += tree.num_nodes();
    ++trees;
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  const double eps = static_cast<double>(expansions) / seconds;
  print_machine_line();
  std::printf("scene %s, strategy %s, %lld trees of %d expansions in %.1f s on one thread\n",
              scene.name.c_str(), o.strategy.c_str(), static_cast<long long>(trees),
              o.expansions_per_tree, seconds);
  std::printf("  %.2f M expansions/s, %.2f M nodes kept/s, %.1f M frame checks/s, mean tree %.0f "
              "nodes, %zu bytes per node\n",
              eps / 1e6, static_cast<double>(nodes) / seconds / 1e6,
              static_cast<double>(frame_checks) / seconds / 1e6, size_sum / static_cast<double>(trees),
              MotionTree::bytes_per_node());
  if (o.json)
    print_json_line({{"bench", "lookahead"},
                     {"scene", scene.name},
                     {"strategy", o.strategy},
                     {"seconds", rounded(seconds, 3)},
                     {"expansions_per_sec", rounded(eps, 0)},
                     {"nodes_per_sec", rounded(static_cast<double>(nodes) / seconds, 0)},
                     {"frame_checks_per_sec", rounded(static_cast<double>(frame_checks) / seconds, 0)},
                     {"mean_tree_nodes", rounded(size_sum / static_cast<double>(trees), 1)},
                     {"nodes_bytes", MotionTree::bytes_per_node()}});
  return 0;
}

}  // namespace foresight::bench

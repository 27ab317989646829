// foresight-bench: measured figures for docs/PERFORMANCE.md.
//   foresight-bench collision [--scene maze] [--seconds 3] [--json]
//   foresight-bench bvh [--file F] [--json]
//   foresight-bench graph --motions DIR [--json]
#include "bench_commands.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>

namespace foresight::bench {

double median(std::vector<double>& samples) {
  if (samples.empty()) return 0.0;
  const size_t mid = samples.size() / 2;
  std::nth_element(samples.begin(), samples.begin() + static_cast<long>(mid), samples.end());
  return samples[mid];
}

}  // namespace foresight::bench

int main(int argc, char** argv) {
  using namespace foresight::bench;
  CLI::App app{"foresight-bench: Foresight's benchmarks (figures go to docs/PERFORMANCE.md)"};
  app.require_subcommand(1);

  CollisionBenchOptions collision;
  auto* c = app.add_subcommand("collision", "Random clip placements checked against a scene");
  c->add_option("--scene", collision.scene, "Built-in scene name or scene .json path");
  c->add_option("--seconds", collision.seconds, "Measured seconds")->check(CLI::Range(0.1, 600.0));
  c->add_option("--seed", collision.seed, "Placement seed");
  c->add_option("--motions", collision.motions, "BVH folder instead of the default library");
  c->add_flag("--json", collision.json, "Print one JSON object as the last line");

  BvhBenchOptions bvh;
  auto* b = app.add_subcommand("bvh", "BVH parse + import time of one file");
  b->add_option("--file", bvh.file, "BVH file (default: the largest under ../shared/mocap)");
  b->add_option("--runs", bvh.runs, "Repetitions (median reported)")->check(CLI::Range(1, 10000));
  b->add_flag("--json", bvh.json, "Print one JSON object as the last line");

  GraphBenchOptions graph;
  auto* g = app.add_subcommand("graph", "Automatic motion graph build time on a BVH folder");
  g->add_option("--motions", graph.motions, "Folder of BVH clips")->required();
  g->add_option("--runs", graph.runs, "Repetitions (median reported)")->check(CLI::Range(1, 100));
  g->add_flag("--json", graph.json, "Print one JSON object as the last line");

  CLI11_PARSE(app, argc, argv);
  if (*c) return bench_collision(collision);
  if (*b) return bench_bvh(bvh);
  return bench_graph(graph);
}

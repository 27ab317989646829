// foresight-bench: measured figures for docs/PERFORMANCE.md.
//   foresight-bench collision [--scene maze] [--seconds 3] [--json]
//   foresight-bench bvh [--file F] [--json]
//   foresight-bench graph --motions DIR [--json]
//   foresight-bench lookahead [--scene maze] [--strategy command] [--json]
//   foresight-bench client [--avatars 1000] [--seconds 3] [--json]   (when foresight_client is built)
//   foresight-bench fighter [--figure DIR] [--json]
//   foresight-bench terrain [--seed 1] [--json]
//   foresight-bench motion-quality [--scene maze] [--goal NAME] [--motions DIR] [--seeds 10] [--shift-steps M] [--json]
//   foresight-bench snapshot [--avatars 1000] [--receivers 200] [--view 50] [--json]
//   foresight-bench load-report out/loadtest/bots-*.txt [--out out/loadtest]
#include "bench_commands.hpp"
#include "library_build/motion_source_cli.hpp"
#include "terrain_bench.hpp"

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

  LookaheadBenchOptions lookahead;
  auto* l = app.add_subcommand("lookahead", "Feasible motion tree growth on one core");
  l->add_option("--scene", lookahead.scene, "Built-in scene name or scene .json path");
  l->add_option("--strategy", lookahead.strategy, "Exploration strategy (name or 0-4)");
  l->add_option("--seconds", lookahead.seconds, "Measured seconds")->check(CLI::Range(0.1, 600.0));
  l->add_option("--expansions-per-tree", lookahead.expansions_per_tree,
                "Expansions before the tree is re-rooted elsewhere")->check(CLI::Range(1, 100000000));
  l->add_option("--seed", lookahead.seed, "Placement seed");
  l->add_flag("--json", lookahead.json, "Print one JSON object as the last line");

#ifdef FORESIGHT_HAVE_CLIENT
  ClientBenchOptions client;
  auto* cl = app.add_subcommand("client", "Client frame CPU work: snapshot buffer sample + pose rebuild of N avatars");
  cl->add_option("--avatars", client.avatars, "Avatars")->check(CLI::Range(1, 100000));
  cl->add_option("--seconds", client.seconds, "Measured seconds")->check(CLI::Range(0.1, 600.0));
  cl->add_option("--seed", client.seed, "Seed of spawns and successor choices");
  cl->add_flag("--json", client.json, "Print one JSON object as the last line");
#endif

  FighterBenchOptions fighter;
  auto* fi = app.add_subcommand("fighter", "NPC fighter: strike retrieval (75 / 10,000 entries) and adaptation");
  fi->add_option("--queries", fighter.queries, "Timed retrievals per database")->check(CLI::Range(100, 10000000));
  fi->add_option("--seed", fighter.seed, "Seed of queries and targets");
  fi->add_option("--figure", fighter.figure_dir, "Also write the adapted strikes on five morphologies (SVG) here");
  fi->add_flag("--json", fighter.json, "Print one JSON object as the last line");

  TerrainBenchCommand terrain;
  auto* te = app.add_subcommand("terrain", "Footstep and upper-body planning on the terrain scene and seeded profiles");
  te->add_option("--scene", terrain.options.scene, "Built-in scene name or scene .json path");
  te->add_option("--window", terrain.options.window_steps, "Footstep window n")->check(CLI::Range(1, 4));
  te->add_option("--intervals", terrain.options.intervals, "Step length intervals m")->check(CLI::Range(1, 16));
  te->add_option("--seed", terrain.options.seed, "Seed of paths and profiles");
  te->add_option("--upper-budget", terrain.options.upper_body_budget, "Upper-body collision checks per part")
      ->check(CLI::Range(1, 10000000));
  te->add_flag("--json", terrain.json, "Print one JSON object as the last line");

  MotionQualityBenchOptions quality;
  auto* mq = app.add_subcommand("motion-quality", "Closed-loop players: foot skate, pops, limits, response on the shown poses");
  mq->add_option("--scene", quality.scene, "Built-in scene name or scene .json path");
  mq->add_option("--goal", quality.goal, "The scene's goal to walk to, by name (default: its first)");
  foresight::add_motion_source_options(*mq, quality.motions);
  mq->add_option("--seeds", quality.seeds, "Closed-loop player seeds per controller")->check(CLI::Range(1, 1000));
  mq->add_option("--max-seconds", quality.max_seconds, "Time cap of a run")->check(CLI::Range(1.0, 3600.0));
  mq->add_option("--shift-steps", quality.shift_steps_m, "Move the scene's step blocks this far along z (m)")
      ->check(CLI::Range(-10.0, 10.0));
  mq->add_flag("--json", quality.json, "Print one JSON object as the last line");

  SnapshotBenchOptions snapshot;
  auto* sn = app.add_subcommand("snapshot", "Packed snapshot avatars: the server's coding and the client's decoding per avatar");
  sn->add_option("--avatars", snapshot.avatars, "Avatars in the world")->check(CLI::Range(1, 100000));
  sn->add_option("--receivers", snapshot.receivers, "Clients")->check(CLI::Range(1, 10000));
  sn->add_option("--view", snapshot.view, "Avatars in each client's view")->check(CLI::Range(1, 100000));
  sn->add_option("--snapshots", snapshot.snapshots, "Timed snapshots")->check(CLI::Range(1, 100000));
  sn->add_option("--seed", snapshot.seed, "Seed of the world and the views");
  sn->add_flag("--json", snapshot.json, "Print one JSON object as the last line");

  LoadReportOptions load;
  auto* lr = app.add_subcommand("load-report", "Table, CSV and chart from foresight-bots --json outputs (scripts/loadtest)");
  lr->add_option("inputs", load.inputs, "Files ending in a foresight-bots --json line")->required();
  lr->add_option("--out", load.out_dir, "Folder for loadtest.csv and loadtest.svg");

  CLI11_PARSE(app, argc, argv);
  if (*lr) return bench_load_report(load);
  if (*sn) return bench_snapshot(snapshot);
  if (*mq) return bench_motion_quality(quality);
#ifdef FORESIGHT_HAVE_CLIENT
  if (*cl) return bench_client(client);
#endif
  if (*l) return bench_lookahead(lookahead);
  if (*fi) return bench_fighter(fighter);
  if (*te) return bench_terrain(terrain);
  if (*c) return bench_collision(collision);
  if (*b) return bench_bvh(bvh);
  return bench_graph(graph);
}

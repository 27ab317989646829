// foresight-record: generate a recording with the scripted player (recording_generator.hpp).
//   foresight-record --scene maze --seed 1 --out data/recordings/maze_train.json
//                    [--goal NAME] [--spawn NAME] [--motions DIR] [--name NAME]
//                    [--budget 200] [--max-seconds 240] [--steer-deg-per-s 0] [--trace PATH.csv]
// Prints the route length, the duration, the samples and whether the goal was reached; exits 0
// when it was, 2 when the recording was written but the goal not reached, 1 on errors.
#include "library_build/library_source.hpp"
#include "scripted/recording_generator.hpp"
#include "world/collision_world.hpp"
#include "world/data_paths.hpp"
#include "world/scene_load.hpp"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>

int main(int argc, char** argv) {
  using namespace foresight;
  CLI::App app{"foresight-record: record a scripted player steering the look-ahead avatar to a goal"};
  RecordingGeneratorConfig config;
  std::string scene_name = "maze", out, motions, trace;
  app.add_option("--scene", scene_name, "Built-in scene name or scene .json path")->capture_default_str();
  app.add_option("--seed", config.seed, "Seed of the player's behaviour")->capture_default_str();
  app.add_option("--out", out, "Recording file to write")->required();
  app.add_option("--goal", config.goal, "Goal point name (default: the scene's first)");
  app.add_option("--spawn", config.spawn, "Spawn point name (default: the scene's first)");
  app.add_option("--name", config.name, "Recording name (default: the output file's stem)");
  app.add_option("--motions", motions, "Folder of BVH clips instead of the built-in default library")
      ->check(CLI::ExistingDirectory);
  app.add_option("--budget", config.replay.expansions_per_frame, "Tree expansions per 30 fps frame")
      ->check(CLI::Range(int64_t{0}, int64_t{1} << 30))
      ->capture_default_str();
  config.replay.max_seconds = 240;
  app.add_option("--max-seconds", config.replay.max_seconds, "Time cap of the recording")
      ->check(CLI::Range(1.0, 36000.0))
      ->capture_default_str();
  float steer_deg_per_s = 0.0f;
  app.add_option("--steer-deg-per-s", steer_deg_per_s,
                 "Root steering of the avatar between segment ends (MotionTreeConfig::steer_rad_per_s; 0: off)")
      ->check(CLI::Range(0.0f, 3600.0f))
      ->capture_default_str();
  app.add_option("--trace", trace, "Also write the avatar's root and segment per frame (CSV: t, x, z, segment) here");
  CLI11_PARSE(app, argc, argv);
  config.replay.tree.steer_rad_per_s = radians(steer_deg_per_s);

  MotionSource source;
  source.motions_dir = motions;
  MotionLibrary lib;
  Scene scene;
  CollisionWorld world;
  std::string error;
  if (!motion_library_load(source, lib, error) ||
      !scene_world_load(scene_name, scene, world, error)) {
    std::fprintf(stderr, "foresight-record: %s\n", error.c_str());
    return 1;
  }
  config.scene = scene_name;
  if (config.name.empty()) config.name = std::filesystem::path(out).stem().string();

  GeneratedRecording g;
  if (!recording_generate(lib, scene, world, config, g, error)) {
    std::fprintf(stderr, "foresight-record: %s\n", error.c_str());
    return 1;
  }
  if (!recording_save(out, g.recording, error)) {
    std::fprintf(stderr, "foresight-record: %s\n", error.c_str());
    return 1;
  }
  if (!trace.empty()) {
    std::FILE* f = std::fopen(trace.c_str(), "w");
    if (f == nullptr) {
      std::fprintf(stderr, "foresight-record: %s: cannot open for writing\n", trace.c_str());
      return 1;
    }
    std::fprintf(f, "t,x,z,segment\n");
    for (size_t i = 0; i < g.run.path.size(); ++i)
      std::fprintf(f, "%.4f,%.4f,%.4f,%s\n", static_cast<double>(i) * config.replay.frame_interval_s,
                   g.run.path[i].x, g.run.path[i].y, lib.graph.segments[g.run.segments[i]].name.c_str());
    std::fclose(f);
  }
  std::printf("%s: scene %s, spawn (%.2f, %.2f) -> goal (%.2f, %.2f), seed %llu, library %s\n", out.c_str(),
              scene.name.c_str(), g.recording.start_pos_m.x, g.recording.start_pos_m.y, g.recording.goal_pos_m.x,
              g.recording.goal_pos_m.y, static_cast<unsigned long long>(config.seed), lib.name.c_str());
  std::printf("  route %.1f m, %zu waypoints (body height %.2f m)\n", g.route_length_m, g.route.size(),
              g.route_body_height_m);
  std::printf("   ");
  for (const vec2& w : g.route) std::printf(" (%.2f, %.2f)", w.x, w.y);
  std::printf("\n  duration %.2f s, %zu samples, goal %s", g.recording.duration_s(), g.recording.samples.size(),
              g.reached_goal ? "reached" : "NOT reached");
  if (g.reached_goal) std::printf(" at %.2f s", g.run.time_to_goal_s);
  std::printf("\n  avatar: %.1f m walked, %d fallbacks, %d stalls, %lld colliding frames, mean tree %.0f nodes\n",
              [&] {
                double d = 0;
                for (size_t i = 1; i < g.run.path.size(); ++i) d += glm::length(g.run.path[i] - g.run.path[i - 1]);
                return d;
              }(),
              g.run.fallbacks, g.run.stalls, static_cast<long long>(g.run.colliding_frames), g.run.avg_tree_size);
  return g.reached_goal ? 0 : 2;
}

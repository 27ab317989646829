// steer: an avatar steered by a recorded player through a scene with look-ahead, headless,
// printing every motion it starts and the size of its feasible motion tree.
#include "commands.hpp"
#include "scripted/recording.hpp"
#include "scripted/replay.hpp"
#include "world/data_paths.hpp"
#include "world/scene_load.hpp"

#include <algorithm>
#include <filesystem>
#include <cstdio>

namespace foresight::tools {

int command_steer(const MotionSource& source, const SteerOptions& o) {
  MotionLibrary lib;
  if (!load_library_or_report(source, lib)) return 1;
  Recording recording;
  Scene scene;
  CollisionWorld world;
  std::string error;
  Strategy strategy;
  if (!strategy_parse(o.strategy, strategy, error) || !recording_load(o.recording, recording, error) ||
      !scene_world_load(recording.scene, scene, world, error)) {
    std::fprintf(stderr, "foresight-motion: %s\n", error.c_str());
    return 1;
  }
  ReplayConfig config;
  config.tree.strategy = strategy;
  config.expansions_per_frame = o.expansions_per_frame;
  config.max_seconds = o.max_seconds;
  if (uses_statistics(strategy)) {
    // As the lab does: learn from a training recording replayed with command matching.
    std::filesystem::path train_path = o.train;
    if (train_path.empty()) {
      train_path = data_dir() / "recordings" / (recording.scene + "_train.json");
      if (!std::filesystem::exists(train_path)) train_path = o.recording;
    }
    Recording train;
    if (!recording_load(train_path, train, error)) {
      std::fprintf(stderr, "foresight-motion: training recording: %s\n", error.c_str());
      return 1;
    }
    ReplayConfig learn = config;
    learn.tree.strategy = Strategy::kCommand;
    config.statistics = learn_statistics(lib, world, train, learn);
    if (config.statistics.empty()) {
      std::fprintf(stderr, "foresight-motion: could not learn statistics from %s\n", train_path.string().c_str());
      return 1;
    }
    std::printf("statistics learned from %s\n", train_path.string().c_str());
  }
  ReplayRun run(lib, world, {recording.start_pos_m, recording.start_heading_rad},
                recording.goal_pos_m, recording.goal_radius_m, config);
  if (!run.ok()) {
    std::fprintf(stderr, "foresight-motion: %s\n", run.error().c_str());
    return 1;
  }
  std::printf("recording %s in %s: %zu commands over %.1f s; strategy %s, %lld expansions per "
              "frame at %.0f fps\n",
              recording.name.c_str(), scene.name.c_str(), recording.samples.size(),
              recording.duration_s(), o.strategy.c_str(),
              static_cast<long long>(o.expansions_per_frame), 1.0 / config.frame_interval_s);
  // Like replay_recording: the keys end with the recording, the avatar gets the grace after.
  const double end_s = recording.duration_s() + config.grace_after_end_s;
  int last_segment = -1;
  while (!run.done() && run.time_s() <= end_s) {
    const double t = run.time_s();
    const ControlInput input = recording_input_at(recording, t);
    run.frame(input);
    const LookaheadAvatar& avatar = run.avatar();
    if (avatar.playback().segment == last_segment) continue;
    last_segment = avatar.playback().segment;
    const Placement at = avatar.root();
    const MotionTree& tree = avatar.tree();
    std::printf("  t=%6.2fs  %-24s at (%6.2f, %6.2f) heading %+7.1f deg  tree %5d nodes, depth %d%s\n",
                t, lib.graph.segments[last_segment].name.c_str(), at.pos_m.x, at.pos_m.y,
                degrees(at.heading_rad), tree.num_nodes(), tree.max_depth_reached(),
                input.camera_dir == vec2(0.0f) ? "  (no key pressed)" : "");
  }
  ReplayResult r = run.finish();
  std::vector<double> ms = response_ms(r);
  std::sort(ms.begin(), ms.end());
  const auto pct = [&](double p) { return ms.empty() ? 0.0 : ms[static_cast<size_t>(p * (ms.size() - 1))]; };
  std::printf("%s after %.1f s; mean tree %.0f nodes; %d stops with nothing feasible; %lld colliding "
              "frames; command-to-motion angle %.1f deg; response p50 %.0f ms, p95 %.0f ms\n",
              r.reached_goal ? "goal reached" : "goal NOT reached",
              r.reached_goal ? r.time_to_goal_s : r.seconds, r.avg_tree_size, r.fallbacks,
              static_cast<long long>(r.colliding_frames), r.mean_command_angle_deg, pct(0.5), pct(0.95));
  return r.colliding_frames == 0 ? 0 : 1;
}

}  // namespace foresight::tools

// Loading, the spare-time model, statistics, today's expansion rate, and run_lab.
#include "lab/lab_experiments.hpp"

#include "lab/lab_driver.hpp"
#include "lab/lab_internal.hpp"
#include "library_build/library_source.hpp"
#include "world/data_paths.hpp"
#include "world/scene_load.hpp"

#include <algorithm>
#include <cmath>

namespace foresight::lab {

using namespace detail;

double SpareTimeModel::spare_s(double interval_s) const {
  return std::max(0.0, interval_s - frame_cost_s);
}

int64_t SpareTimeModel::expansions_per_frame(double interval_s) const {
  return static_cast<int64_t>(std::llround(spare_s(interval_s) * expansions_per_s));
}

std::vector<double> lab_intervals(const LabOptions& options) {
  if (!options.intervals_s.empty()) return options.intervals_s;
  if (options.quick) return {1.0 / 30, 1.0 / 15, 1.0 / 10};
  return {1.0 / 60, 1.0 / 40, 1.0 / 30, 1.0 / 20, 1.0 / 15, 1.0 / 12, 1.0 / 10};
}

bool lab_load(const std::string& scene_name, const MotionSource& motions, LabScene& out, std::string& error) {
  out.name = scene_name;
  if (!motion_library_load(motions, out.library, error)) return false;
  if (!scene_world_load(scene_name, out.scene, out.world, error)) return false;
  const std::filesystem::path dir = data_dir() / "recordings";
  std::string why;
  if (!recording_load(dir / (scene_name + "_train.json"), out.train, why)) {
    error = "training recording: " + why;
    return false;
  }
  if (!recording_load(dir / (scene_name + "_eval.json"), out.eval, why)) {
    error = "evaluation recording: " + why;
    return false;
  }
  return true;
}

ReplayConfig lab_replay_config(const MotionTreeConfig& tree, double interval_s,
                               int64_t expansions_per_frame) {
  ReplayConfig c;
  c.tree = tree;
  c.frame_interval_s = interval_s;
  c.expansions_per_frame = expansions_per_frame;
  c.wall_clock_spare_s = 0.0;  // deterministic: expansions only
  return c;
}

TransitionStatistics lab_learn_statistics(const LabScene& lab, const LabOptions& options) {
  MotionTreeConfig tree = options.tree;
  tree.strategy = Strategy::kCommand;
  ReplayConfig c = lab_replay_config(tree, options.navigation_interval_s,
                                     options.navigation_expansions_per_frame);
  return learn_statistics(lab.library, lab.world, lab.train, c);
}

// ---- Today's expansion rate -----------------------------------------------------------------

RateMeasurement measure_expansion_rate(const LabScene& lab, const LabOptions& options) {
  // Real states along the eval recording (segment, where it started, the command then), so the
  // trees timed here are the trees a replay grows.
  MotionTreeConfig tree_config = options.tree;
  tree_config.strategy = Strategy::kCommand;
  RateMeasurement m;
  const std::vector<DriveState> states = drive_states_at(
      lab.library, lab.world, lab.eval,
      lab_replay_config(tree_config, options.navigation_interval_s,
                        options.navigation_expansions_per_frame),
      evenly_spread_times(lab.eval, 16), m.error);
  if (states.empty()) {
    if (m.error.empty()) m.error = "rate: the eval replay played no frame";
    return m;
  }
  MotionTree tree(lab.library, lab.world, tree_config);
  const Clock::time_point t0 = Clock::now();
  size_t next = 0;
  do {
    const DriveState& s = states[next];
    next = (next + 1) % states.size();
    tree.reset(s.segment, s.segment_start, s.incoming_transition);
    tree.set_command(s.command_world, s.avatar);
    m.expansions += tree.grow(GrowBudget::expansions(INT64_MAX)).expansions;
    ++m.trees;
  } while (seconds_since(t0) < options.rate_measure_s);
  m.seconds = seconds_since(t0);
  m.expansions_per_s = static_cast<double>(m.expansions) / m.seconds;
  return m;
}

LabResult run_lab(const LabScene& lab, const LabOptions& options_in) {
  const Clock::time_point t0 = Clock::now();
  LabOptions options = options_in;
  if (options.quick) options.rate_measure_s = std::min(options.rate_measure_s, 0.1);
  LabResult r;
  r.scene = lab.name;
  r.options = options;
  r.recordings_match_library = lab.train.library_hash == lab.library.content_hash &&
                               lab.eval.library_hash == lab.library.content_hash;
  Clock::time_point t = Clock::now();
  auto phase = [&](const char* name) {
    r.phase_s.emplace_back(name, seconds_since(t));
    t = Clock::now();
  };
  const TransitionStatistics statistics = lab_learn_statistics(lab, options);
  phase("statistics");
  r.fig9 = run_fig9(lab, options, statistics);
  phase("fig9");
  r.fig10 = run_fig10(lab, options, statistics);
  phase("fig10");
  r.navigation = run_navigation(lab, options, statistics);
  phase("navigation");
  r.closed_loop = run_closed_loop_navigation(lab, options, statistics);
  phase("closed-loop");
  MotionQualityOptions quality;
  quality.seeds = options.quick ? 1 : std::min(options.closed_loop_seeds, 10);
  std::string quality_error;
  r.motion_quality = measure_motion_quality(lab.library, lab.scene, lab.world,
                                            motion_quality_controllers(radians(kLabSteerDegPerS)), quality, quality_error);
  phase("motion-quality");
  for (const std::string* e : {&r.fig9.error, &r.fig10.error, &r.navigation.error, &r.closed_loop.error, &quality_error})
    if (!e->empty() && r.error.empty()) r.error = *e;
  if (statistics.empty() && r.error.empty()) r.error = "learning statistics from the training recording failed";
  r.wall_s = seconds_since(t0);
  return r;
}

}  // namespace foresight::lab

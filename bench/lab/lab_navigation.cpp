// Navigation efficiency and responsiveness: replayed recordings and the closed loop.
#include "lab/lab_experiments.hpp"

#include "lab/lab_internal.hpp"
#include "scripted/recording_generator.hpp"

#include <algorithm>
#include <cmath>

namespace foresight::lab {

using namespace detail;

// ---- Navigation efficiency and responsiveness -----------------------------------------------

// The "look-ahead 1 + steering" row steers the root (LookaheadAvatar,
// MotionTreeConfig::steer_rad_per_s) at kLabSteerDegPerS.
std::vector<ControllerSpec> lab_controllers(const MotionTreeConfig& base) {
  std::vector<ControllerSpec> out;
  for (int s = 0; s < kNumStrategies; ++s) {
    MotionTreeConfig c = base;
    c.strategy = static_cast<Strategy>(s);
    out.push_back({"look-ahead " + strategy_label(s), c, true, true});
  }
  {
    MotionTreeConfig c = base;
    c.strategy = Strategy::kCommand;
    c.steer_rad_per_s = radians(kLabSteerDegPerS);
    out.push_back({kResponsiveController, c, true, true});
  }
  MotionTreeConfig greedy = base;
  greedy.strategy = Strategy::kCommand;
  out.push_back({"greedy depth-1", greedy_depth1_config(greedy), false, true});
  out.push_back({"naive FSM", naive_fsm_config(base), false, false});
  return out;
}

namespace {

/// Adds one run to the rows, the controller's summary and the recording's verdicts.
void add_run(NavigationResult& r, std::vector<double>& pooled, ControllerSummary& sum,
             const ControllerSpec& spec, const std::string& label, const ReplayResult& res,
             const MotionGraph& graph, bool& naive_reached, bool& all_lookahead_reached) {
  NavigationRow row;
  row.recording = label;
  row.controller = spec.name;
  row.lookahead = spec.lookahead;
  row.checks_collisions = spec.checks_collisions;
  row.reached_goal = res.reached_goal;
  row.time_to_goal_s = res.time_to_goal_s;
  row.seconds = res.seconds;
  row.fallbacks = res.fallbacks;
  row.stalls = res.stalls;
  row.recoveries = res.recoveries;
  row.colliding_frames = res.colliding_frames;
  row.mean_command_angle_deg = res.mean_command_angle_deg;
  row.avg_tree_size = res.avg_tree_size;
  const std::vector<double> ms = response_ms(res);
  row.response_ms_p50 = percentile(ms, 50);
  row.response_ms_p95 = percentile(ms, 95);
  auto name = [&](int segment) { return segment >= 0 ? graph.segments[segment].name : std::string(); };
  for (const Response& e : res.responses)
    row.responses.push_back({e.at_s, e.ms, e.change_deg, name(e.segment_at_change), name(e.segment_at_response)});
  r.rows.push_back(std::move(row));

  sum.recordings += 1;
  sum.goals_reached += res.reached_goal ? 1 : 0;
  sum.fallbacks += res.fallbacks;
  sum.stalls += res.stalls;
  sum.recoveries += res.recoveries;
  sum.colliding_frames += res.colliding_frames;
  pooled.insert(pooled.end(), ms.begin(), ms.end());
  if (spec.checks_collisions) r.lookahead_collisions += res.colliding_frames;
  if (spec.lookahead) all_lookahead_reached = all_lookahead_reached && res.reached_goal;
  if (!spec.checks_collisions) naive_reached = res.reached_goal;
}

void finish_summary(NavigationResult& r, const std::vector<std::vector<double>>& pooled) {
  for (size_t k = 0; k < r.summary.size(); ++k) {
    r.summary[k].responses = pooled[k].size();
    r.summary[k].response_ms_p50 = percentile(pooled[k], 50);
    r.summary[k].response_ms_p95 = percentile(pooled[k], 95);
  }
}

}  // namespace

NavigationResult run_navigation(const LabScene& lab, const LabOptions& options,
                                const TransitionStatistics& statistics) {
  NavigationResult r;
  r.mode = "replay";
  r.interval_s = options.navigation_interval_s;
  r.expansions_per_frame = options.navigation_expansions_per_frame;
  const std::vector<ControllerSpec> controllers = lab_controllers(options.tree);
  std::vector<std::vector<double>> pooled(controllers.size());
  for (const ControllerSpec& spec : controllers)
    r.summary.push_back({.controller = spec.name, .lookahead = spec.lookahead, .checks_collisions = spec.checks_collisions});
  const std::pair<const char*, const Recording*> recordings[] = {{"train", &lab.train},
                                                                  {"eval", &lab.eval}};
  for (const auto& [label, rec] : recordings) {
    bool naive_reached = true;
    bool all_lookahead_reached = true;
    for (size_t k = 0; k < controllers.size(); ++k) {
      const ControllerSpec& spec = controllers[k];
      ReplayConfig c = lab_replay_config(spec.tree, r.interval_s, r.expansions_per_frame);
      c.stop_at_goal = true;
      if (uses_statistics(spec.tree.strategy)) c.statistics = statistics;
      const ReplayResult res = replay_recording(lab.library, lab.world, *rec, c);
      if (!res.error.empty() && r.error.empty()) r.error = res.error;
      add_run(r, pooled[k], r.summary[k], spec, label, res, lab.library.graph, naive_reached,
              all_lookahead_reached);
    }
    if (!naive_reached) {
      r.naive_stuck.push_back(label);
      r.lookahead_reached_where_naive_stuck = r.lookahead_reached_where_naive_stuck && all_lookahead_reached;
    }
  }
  finish_summary(r, pooled);
  return r;
}

namespace {

/// The scene point nearest to `p` (its name), for matching a recording's spawn and goal.
template <typename Points>
std::string nearest_name(const Points& points, vec2 p) {
  std::string name;
  float best = 0.0f;
  for (const auto& q : points) {
    const float d = glm::length(q.pos_m - p);
    if (name.empty() || d < best) name = q.name, best = d;
  }
  return name;
}

}  // namespace

NavigationResult run_closed_loop_navigation(const LabScene& lab, const LabOptions& options,
                                            const TransitionStatistics& statistics) {
  NavigationResult r;
  r.mode = "closed-loop";
  r.interval_s = 1.0 / 30.0;  // the generator's frame rate
  r.expansions_per_frame = options.navigation_expansions_per_frame;
  const std::vector<ControllerSpec> controllers = lab_controllers(options.tree);
  std::vector<std::vector<double>> pooled(controllers.size());
  for (const ControllerSpec& spec : controllers)
    r.summary.push_back({.controller = spec.name, .lookahead = spec.lookahead, .checks_collisions = spec.checks_collisions});
  // The responsive controller, whose p95 the bar is read from, gets more seeds: its p95 sits on a
  // flat shoulder of the distribution, so twenty runs' figure moves by a frame or two with the
  // sample (docs/LAB.md). Its extra runs are fast (small trees).
  const int seeds = options.quick ? 1 : std::max(1, options.closed_loop_seeds);
  const int responsive_seeds = options.quick ? 1 : std::max(seeds, options.responsive_seeds);
  auto seeds_of = [&](const ControllerSpec& spec) {
    return spec.name == kResponsiveController ? responsive_seeds : seeds;
  };
  for (uint64_t seed = 1; seed <= static_cast<uint64_t>(responsive_seeds); ++seed) {
    const std::string label = "seed " + std::to_string(seed);
    bool naive_reached = true;
    bool all_lookahead_reached = true;
    for (size_t k = 0; k < controllers.size(); ++k) {
      const ControllerSpec& spec = controllers[k];
      if (seed > static_cast<uint64_t>(seeds_of(spec))) continue;
      RecordingGeneratorConfig g;
      g.scene = lab.name;
      g.name = "closed-loop";
      g.spawn = nearest_name(lab.scene.spawns, lab.eval.start_pos_m);
      g.goal = nearest_name(lab.scene.goals, lab.eval.goal_pos_m);
      g.seed = seed;
      g.replay = lab_replay_config(spec.tree, r.interval_s, r.expansions_per_frame);
      g.replay.max_seconds = options.closed_loop_max_s;
      if (uses_statistics(spec.tree.strategy)) g.replay.statistics = statistics;
      GeneratedRecording out;
      std::string error;
      if (!recording_generate(lab.library, lab.scene, lab.world, g, out, error)) {
        if (r.error.empty()) r.error = error;
        continue;
      }
      add_run(r, pooled[k], r.summary[k], spec, label, out.run, lab.library.graph, naive_reached,
              all_lookahead_reached);
    }
    if (!naive_reached) {
      r.naive_stuck.push_back(label);
      r.lookahead_reached_where_naive_stuck = r.lookahead_reached_where_naive_stuck && all_lookahead_reached;
    }
  }
  finish_summary(r, pooled);
  return r;
}

}  // namespace foresight::lab

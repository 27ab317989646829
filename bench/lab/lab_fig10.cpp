// Fig. 10: the future positions each strategy keeps, from one common state.
#include "lab/lab_experiments.hpp"

#include "lab/lab_driver.hpp"
#include "lab/lab_internal.hpp"

#include <algorithm>
#include <cmath>

namespace foresight::lab {

using namespace detail;

// ---- Fig. 10 --------------------------------------------------------------------------------

Fig10Result run_fig10(const LabScene& lab, const LabOptions& options,
                      const TransitionStatistics& statistics) {
  Fig10Result r;
  const SpareTimeModel paper{options.frame_cost_s, options.paper_expansions_per_s};
  r.interval_s = options.fig10_interval_s;
  r.expansions_per_frame = paper.expansions_per_frame(r.interval_s);
  r.grow_frames = std::max(1, static_cast<int>(std::lround(1.0 / r.interval_s)));

  MotionTreeConfig reference = options.tree;
  reference.strategy = Strategy::kCommand;
  // Candidates every 0.25 s from the chosen fraction of the recording on; the first with a steady
  // command (held >= 1 s) within 45 deg of the avatar's facing is taken, as in the paper's
  // "consistent commands of walking forward in the past few steps"; else the first candidate.
  const Recording& rec = lab.eval;
  std::vector<double> times;
  for (double t = options.fig10_time_fraction * rec.duration_s(); t <= rec.duration_s(); t += 0.25)
    times.push_back(t);
  if (times.empty()) times.push_back(rec.duration_s());
  const std::vector<DriveState> states = drive_states_at(
      lab.library, lab.world, rec,
      lab_replay_config(reference, options.navigation_interval_s,
                        options.navigation_expansions_per_frame),
      times, r.error);
  if (states.empty()) {
    if (r.error.empty()) r.error = "fig10: the replay ended before the snapshot time";
    return r;
  }
  auto steady_forward = [&](const DriveState& st) {
    const auto it = std::upper_bound(rec.samples.begin(), rec.samples.end(), st.time_s,
                                     [](double t, const CommandSample& c) { return t < c.t_s; });
    if (it == rec.samples.begin() || st.time_s - std::prev(it)->t_s < 1.0) return false;
    const float len = glm::length(st.command_world);
    const vec2 facing(std::sin(st.avatar.heading_rad), std::cos(st.avatar.heading_rad));
    return len > 1e-4f && glm::dot(st.command_world / len, facing) > std::cos(radians(45.0f));
  };
  const auto chosen = std::find_if(states.begin(), states.end(), steady_forward);
  const DriveState& state = chosen != states.end() ? *chosen : states.front();
  r.time_s = state.time_s;
  r.avatar = state.avatar;
  r.segment = state.segment;
  r.command_world = state.command_world;

  for (int s = 0; s < kNumStrategies; ++s) {
    MotionTreeConfig config = options.tree;
    config.strategy = static_cast<Strategy>(s);
    MotionTree tree(lab.library, lab.world, config);
    if (uses_statistics(config.strategy)) tree.set_statistics(statistics);
    tree.reset(state.segment, state.segment_start, state.incoming_transition);
    for (int f = 0; f < r.grow_frames; ++f) {
      tree.set_command(state.command_world, state.avatar);
      tree.grow(GrowBudget::expansions(r.expansions_per_frame));
    }
    Fig10Panel panel;
    panel.strategy = config.strategy;
    tree.for_each_node([&](int, const MotionTreeNode& n) {
      panel.end_positions_m.push_back(n.end.pos_m);
      panel.depths.push_back(n.depth);
      panel.max_depth = std::max(panel.max_depth, static_cast<int>(n.depth));
    });
    r.panels.push_back(std::move(panel));
  }
  return r;
}

}  // namespace foresight::lab

#include "lab/lab_driver.hpp"

#include "world/collision_check.hpp"

#include <algorithm>
#include <cmath>

namespace foresight::lab {

std::vector<DriveState> drive_states_at(const MotionLibrary& library, const CollisionWorld& world,
                                        const Recording& recording, const ReplayConfig& config,
                                        const std::vector<double>& times_s, std::string& error) {
  std::vector<DriveState> states;
  ReplayRun run(library, world, Placement{recording.start_pos_m, recording.start_heading_rad},
                recording.goal_pos_m, recording.goal_radius_m, config);
  if (!run.ok()) {
    error = run.error();
    return states;
  }
  double played_s = 0.0;
  for (double target : times_s) {
    while (!run.done() && run.time_s() <= target) {
      played_s = run.time_s();
      run.frame(recording_input_at(recording, played_s));
    }
    if (run.frame_index() == 0) break;  // nothing played (done at once)
    const LookaheadAvatar& a = run.avatar();
    DriveState s;
    s.time_s = played_s;
    s.segment = a.playback().segment;
    s.segment_start = a.playback().segment_start;
    s.incoming_transition = a.playback().incoming_transition;
    s.avatar = a.root();
    s.command_world = control_world_direction(a.input());
    states.push_back(s);
    if (run.done()) break;
  }
  return states;
}

std::vector<double> evenly_spread_times(const Recording& recording, int count) {
  std::vector<double> times;
  const double duration = recording.duration_s();
  for (int i = 0; i < count; ++i) times.push_back(count > 1 ? duration * i / (count - 1) : 0.0);
  return times;
}

}  // namespace foresight::lab

namespace foresight::lab {

TreeTurnover drive_turnover(const MotionLibrary& library, const CollisionWorld& world,
                            const Recording& recording, const ReplayConfig& config,
                            std::string& error) {
  TreeTurnover out;
  const int segment = find_fallback_segment(library);
  const Placement start{recording.start_pos_m, recording.start_heading_rad};
  if (segment < 0 || !(config.frame_interval_s > 0.0) ||
      !segment_feasible(world, library.segment_shapes[static_cast<size_t>(segment)], start)) {
    error = "turnover: no idle segment, a bad interval or a blocked start";
    return out;
  }
  double fps = library.clips[static_cast<size_t>(library.graph.segments[static_cast<size_t>(segment)].clip)].fps;
  if (!(fps > 0.0)) fps = 30.0;
  LookaheadAvatar avatar(library, world, config.tree, segment, start);
  avatar.tree().set_statistics(config.statistics);
  const double end_s = config.grace_after_end_s >= 0.0
                           ? std::min(config.max_seconds, recording.duration_s() + config.grace_after_end_s)
                           : config.max_seconds;
  int64_t played = 0, frames = 0;
  double size_sum = 0.0, before_sum = 0.0, kept_share_sum = 0.0, depth_sum = 0.0;
  int64_t kept_nodes = 0;
  for (int64_t k = 0; static_cast<double>(k) * config.frame_interval_s <= end_s; ++k) {
    const double t = static_cast<double>(k) * config.frame_interval_s;
    avatar.set_input(recording_input_at(recording, t));
    out.nodes_added += avatar.grow(GrowBudget::expansions(config.expansions_per_frame)).nodes_added;
    size_sum += avatar.tree().num_nodes();
    ++frames;
    const int64_t due = static_cast<int64_t>(std::floor(t * fps + 1e-6));
    for (; played < due; ++played) {
      const int before = avatar.tree().num_nodes();
      const AvatarStepResult step = avatar.step();
      if (!step.segment_changed || step.fallback) continue;
      ++out.advances;
      before_sum += before;
      kept_share_sum += static_cast<double>(avatar.tree().num_nodes()) / before;
      avatar.tree().for_each_node([&](int, const MotionTreeNode& n) {
        depth_sum += n.depth;
        ++kept_nodes;
      });
    }
  }
  if (frames > 0) out.avg_tree_size = size_sum / static_cast<double>(frames);
  if (out.advances > 0) {
    out.mean_size_before_advance = before_sum / out.advances;
    out.mean_kept_share = kept_share_sum / out.advances;
  }
  if (kept_nodes > 0) out.mean_kept_depth = depth_sum / static_cast<double>(kept_nodes);
  return out;
}

}  // namespace foresight::lab

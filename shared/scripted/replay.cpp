#include "scripted/replay.hpp"

#include "library/playback.hpp"
#include "world/collision_check.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace foresight {

ReplayRun::ReplayRun(const MotionLibrary& library, const CollisionWorld& world, const Placement& start,
                     vec2 goal_pos_m, float goal_radius_m, const ReplayConfig& config)
    : library_(library), world_(world), config_(config), goal_pos_m_(goal_pos_m), goal_radius_m_(goal_radius_m) {
  done_ = true;  // until everything checks out
  if (!(config_.frame_interval_s > 0.0 && config_.frame_interval_s <= 10.0) ||
      !std::isfinite(config_.max_seconds) || config_.expansions_per_frame < 0 ||
      !std::isfinite(config_.wall_clock_spare_s)) {
    result_.error = "replay: frame_interval_s must be in (0, 10], max_seconds finite, budgets >= 0";
    return;
  }
  if (!config_.statistics.empty() && config_.statistics.probability.size() != library.graph.transitions.size()) {
    result_.error = "replay: the statistics have " + std::to_string(config_.statistics.probability.size()) +
                    " transitions, the library " + std::to_string(library.graph.transitions.size()) +
                    " (learned with another library?)";
    return;
  }
  const int segment = find_fallback_segment(library);
  if (segment < 0) {
    result_.error = "replay: the library has no idle segment to spawn in";
    return;
  }
  if (!segment_feasible(world, library.segment_shapes[segment], start)) {
    result_.error = "replay: the start (" + std::to_string(start.pos_m.x) + ", " + std::to_string(start.pos_m.y) +
                    ") is not free for the idle segment '" + library.graph.segments[segment].name + "'";
    return;
  }
  fps_ = library.clips[library.graph.segments[segment].clip].fps;
  if (!(fps_ > 0.0)) fps_ = 30.0;
  avatar_.emplace(library, world, config_.tree, segment, start);
  avatar_->tree().set_statistics(config_.statistics);
  response_.emplace(config_.frame_interval_s);
  const double frames = std::max(1.0, std::ceil(config_.max_seconds / config_.frame_interval_s) + 1.0);
  result_.path.reserve(static_cast<size_t>(std::min(frames, 1.0e6)));
  result_.segments.reserve(result_.path.capacity());
  done_ = false;
}

void ReplayRun::frame(const ControlInput& input) {
  if (done_) return;
  const double t = time_s();
  avatar_->set_input(input);
  if (config_.wall_clock_spare_s > 0.0) {
    const auto spare = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(config_.wall_clock_spare_s));
    avatar_->grow(GrowBudget::until(std::chrono::steady_clock::now() + spare));
  } else {
    avatar_->grow(GrowBudget::expansions(config_.expansions_per_frame));
  }
  tree_size_sum_ += avatar_->tree().num_nodes();

  // Clip time follows display time: floor(t * fps) clip frames by t (the epsilon absorbs
  // 1/30 * 30 = 0.99999...).
  const int64_t due = static_cast<int64_t>(std::floor(t * fps_ + 1e-6));
  while (clip_frames_played_ < due) {
    const AvatarStepResult step = avatar_->step();
    ++clip_frames_played_;
    if (step.segment_changed && step.transition >= 0) result_.transitions_taken.push_back(step.transition);
    check_shown_pose();
  }

  const vec2 pos = avatar_->root().pos_m;
  result_.path.push_back(pos);
  result_.segments.push_back(avatar_->playback().segment);
  if (response_->frame(t, control_world_direction(avatar_->input()), pos, avatar_->playback().segment))
    result_.responses.push_back(response_->last());
  count_stalls(t, pos, glm::length(control_world_direction(input)) > 0.0f);
  ++frame_;
  result_.seconds = static_cast<double>(frame_) * config_.frame_interval_s;

  if (!result_.reached_goal && glm::length(pos - goal_pos_m_) <= goal_radius_m_) {
    result_.reached_goal = true;
    result_.time_to_goal_s = t;
    if (config_.stop_at_goal) done_ = true;
  }
  if (time_s() > config_.max_seconds) done_ = true;
}

void ReplayRun::count_stalls(double t, vec2 pos, bool key_held) {
  if (!key_held) {
    stall_watch_ = false;  // a player standing still is not stalled
    return;
  }
  if (!stall_watch_ || glm::length(pos - stall_from_) > kStallProgress_m) {
    stall_watch_ = true;
    stall_from_ = pos;
    stall_since_s_ = t;
  } else if (t - stall_since_s_ >= kStallSeconds) {
    ++result_.stalls;
    stall_since_s_ = t;  // the next stall needs another kStallSeconds
  }
}

// The pose actually shown, from FK (blends included), against the scene: the tree's precomputed
// volumes are not trusted here.
void ReplayRun::check_shown_pose() {
  if (shown_pose_collides(library_, world_, avatar_->playback(), check_scratch_))
    ++result_.colliding_frames;
}

ReplayResult ReplayRun::finish() {
  if (avatar_) {
    result_.fallbacks = avatar_->fallbacks();
    result_.recoveries = avatar_->recoveries();
    if (!result_.path.empty()) result_.avg_tree_size = tree_size_sum_ / static_cast<double>(result_.path.size());
    result_.mean_command_angle_deg = response_->mean_command_angle_deg();
  }
  return std::move(result_);
}

std::vector<double> response_ms(const ReplayResult& result) {
  std::vector<double> ms;
  ms.reserve(result.responses.size());
  for (const Response& r : result.responses) ms.push_back(r.ms);
  return ms;
}

ReplayResult replay_recording(const MotionLibrary& library, const CollisionWorld& world,
                              const Recording& recording, const ReplayConfig& config) {
  ReplayRun run(library, world, Placement{recording.start_pos_m, recording.start_heading_rad},
                recording.goal_pos_m, recording.goal_radius_m, config);
  const double end_s = config.grace_after_end_s >= 0.0 ? recording.duration_s() + config.grace_after_end_s
                                                       : config.max_seconds;
  while (!run.done() && run.time_s() <= end_s) run.frame(recording_input_at(recording, run.time_s()));
  return run.finish();
}

TransitionStatistics learn_statistics(const MotionLibrary& library, const CollisionWorld& world,
                                      const Recording& training, const ReplayConfig& config) {
  ReplayConfig c = config;
  c.tree.strategy = Strategy::kCommand;
  c.statistics = {};
  const ReplayResult r = replay_recording(library, world, training, c);
  if (!r.error.empty()) return {};
  return transition_statistics_learn(library.graph, r.transitions_taken);
}

}  // namespace foresight

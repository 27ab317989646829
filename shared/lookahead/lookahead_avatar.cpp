#include "lookahead/lookahead_avatar.hpp"

#include <algorithm>
#include <cmath>

namespace foresight {

int find_fallback_segment(const MotionLibrary& library) {
  int best = -1;
  float best_move = 0.0f;
  for (int s = 0; s < library.graph.num_segments(); ++s) {
    const uint32_t tags = library.graph.segments[s].tags;
    if (!(tags & kTagIdle) || (tags & (kTagCrouch | kTagFight))) continue;
    const float move = glm::length(library.segment_motion[s].end.pos_m);
    if (best < 0 || move < best_move) best = s, best_move = move;
  }
  return best;
}

int find_spawn_segment(const MotionLibrary& library) {
  const int idle = find_fallback_segment(library);
  if (idle >= 0) return idle;
  int best = -1;
  float best_speed = 0.0f;
  for (int s = 0; s < library.graph.num_segments(); ++s) {
    const Segment& seg = library.graph.segments[s];
    if ((seg.tags & kTagFight) || seg.num_frames() <= 0) continue;
    const float speed = glm::length(library.segment_motion[s].end.pos_m) / static_cast<float>(seg.num_frames());
    if (best < 0 || speed < best_speed) best = s, best_speed = speed;
  }
  return best;
}

LookaheadAvatar::LookaheadAvatar(const MotionLibrary& library, const CollisionWorld& world,
                                 MotionTreeConfig config, int start_segment, const Placement& start)
    : library_(library),
      world_(world),
      tree_(library, world, std::move(config)),
      playback_{start_segment, 0, start, -1},
      fallback_segment_(find_fallback_segment(library)) {
  tree_.reset(start_segment, start);
}

void LookaheadAvatar::set_input(const ControlInput& input) {
  if (control_input_valid(input)) {
    input_ = input;
  } else {
    input_ = ControlInput{};  // a broken command stops the avatar rather than steering it anywhere
    ++rejected_inputs_;
  }
  tree_.set_command(control_world_direction(input_), root(), input_.crouch);
}

GrowResult LookaheadAvatar::grow(const GrowBudget& budget) { return tree_.grow(budget); }

void LookaheadAvatar::steer() {
  const vec2 command = control_world_direction(input_);
  if (glm::dot(command, command) < 1e-8f) return;
  const Segment& seg = library_.graph.segments[playback_.segment];
  if (!(seg.tags & kTagLocomotion)) return;
  const Placement now = root();
  const float want = std::atan2(command.x, command.y);  // heading convention: forward = (sin h, cos h)
  const float error = wrap_angle(want - now.heading_rad);
  const float fps = library_.clips[seg.clip].fps;
  const float step = tree_.config().steer_rad_per_s / (fps > 0.0f ? fps : 30.0f);
  // Within 15 deg the clips' own turns do: steering there would regrow the tree every frame.
  if (std::abs(error) < radians(15.0f)) return;
  const float turn = std::clamp(error, -step, step);
  // Rotate the segment's placement about where the root stands now.
  const Placement rotated{now.pos_m + rotate_ground(playback_.segment_start.pos_m - now.pos_m, turn),
                          playback_.segment_start.heading_rad + turn};
  if (!segment_feasible(world_, library_.segment_shapes[playback_.segment], rotated)) return;
  playback_.segment_start = rotated;
  tree_.reset(playback_.segment, rotated, playback_.incoming_transition);
  tree_.set_command(command, root(), input_.crouch);
}

bool LookaheadAvatar::leave_standing_loop() const {
  const vec2 command = control_world_direction(input_);
  if (playback_.frame <= 0 || glm::dot(command, command) < 1e-8f) return false;
  const Segment& seg = library_.graph.segments[playback_.segment];
  const SegmentMotion& m = library_.segment_motion[playback_.segment];
  // A held pose that goes nowhere: every frame is the same, so its end can come at any frame.
  return (seg.tags & kTagIdle) && !(seg.tags & kTagTurn) && glm::length(m.end.pos_m) < 0.01f &&
         std::abs(m.end.heading_rad) < 0.02f;
}

AvatarStepResult LookaheadAvatar::step(const ChildVeto* veto) {
  AvatarStepResult result;
  ++playback_.frame;
  int child = -1;
  if (!playback_at_end(library_, playback_)) {
    if (tree_.config().steer_rad_per_s <= 0.0f) return result;
    if (!leave_standing_loop()) {
      steer();
      return result;
    }
    child = tree_.select_child(veto);
    if (child < 0 || (library_.graph.segments[tree_.node(child).segment].tags & kTagIdle)) return result;
    playback_.frame = library_.graph.segments[playback_.segment].num_frames();  // its end, now
  } else {
    child = tree_.select_child(veto);
  }

  result.segment_changed = true;
  // The naive baseline kept children unchecked: it finds out only now, and stops.
  const bool child_free =
      child >= 0 && (tree_.config().check_collisions ||
                     segment_feasible(world_, library_.segment_shapes[tree_.node(child).segment],
                                      tree_.node(child).start));
  if (child_free) {
    result.transition = tree_.advance_root(child);
    playback_take(library_, playback_, result.transition);
    return result;
  }
  // Nothing feasible ahead: idle where the segment ends, if that is free; else hold the last
  // frame and look again from the same root next frame.
  result.fallback = true;
  ++fallbacks_;
  const Placement here = playback_next_start(library_, playback_);
  if (fallback_segment_ >= 0 &&
      segment_feasible(world_, library_.segment_shapes[fallback_segment_], here) &&
      (veto == nullptr || !veto->blocks(fallback_segment_, here))) {
    playback_ = {fallback_segment_, 0, here, -1};
    tree_.reset(fallback_segment_, here);
  } else {
    playback_.frame = library_.graph.segments[playback_.segment].num_frames() - 1;
    tree_.reset(playback_.segment, playback_.segment_start, playback_.incoming_transition);
  }
  return result;
}

}  // namespace foresight

#pragma once
// Playing a motion library: which segment, which frame, where the segment was placed, and how it
// was entered (for the transition blend). Advancing and taking a transition are the only moves.
#include "library/motion_library.hpp"

namespace foresight {

struct PlaybackState {
  int segment = 0;
  int frame = 0;                ///< Frame within the segment, [0, num_frames).
  Placement segment_start;      ///< World placement of the segment's first frame.
  int incoming_transition = -1; ///< How the segment was entered (-1: spawned into it).
};

/// True when the segment has played its last frame and a successor must be chosen.
inline bool playback_at_end(const MotionLibrary& lib, const PlaybackState& s) {
  return s.frame >= lib.graph.segments[s.segment].num_frames();
}

/// World placement where the current segment's successor will start.
inline Placement playback_next_start(const MotionLibrary& lib, const PlaybackState& s) {
  return s.segment_start.compose(lib.segment_motion[s.segment].end);
}

/// Enters the successor named by `transition` (an index into lib.graph.transitions whose `from`
/// is the current segment), placed where the current segment ends.
inline void playback_take(const MotionLibrary& lib, PlaybackState& s, int transition) {
  s.segment_start = playback_next_start(lib, s);
  s.segment = lib.graph.transitions[transition].to;
  s.frame = 0;
  s.incoming_transition = transition;
}

/// World placement of the avatar's root now.
inline Placement playback_root(const MotionLibrary& lib, const PlaybackState& s) {
  return motion_library_root_at(lib, s.segment, s.frame, s.segment_start);
}

/// Where root steering turns the motion about: where the root stood on the frame shown before
/// this one (the segment's first frame: where it stands). Steering runs after the frame has
/// advanced, so turning about that point sends this frame's own step the new way: the command
/// moves the avatar on the frame it arrives, not one frame later.
inline vec2 playback_steer_pivot(const MotionLibrary& lib, const PlaybackState& s) {
  PlaybackState before = s;
  before.frame = s.frame > 0 ? s.frame - 1 : 0;
  return playback_root(lib, before).pos_m;
}

/// The playing segment's start turned by `turn` (rad) about playback_steer_pivot: root
/// steering's rotation of the motion (LookaheadAvatar), the segment playing on from there.
inline Placement playback_turned_start(const MotionLibrary& lib, const PlaybackState& s, float turn) {
  const vec2 pivot = playback_steer_pivot(lib, s);
  return {pivot + rotate_ground(s.segment_start.pos_m - pivot, turn), s.segment_start.heading_rad + turn};
}

/// The current pose (pelvis in world space).
inline void playback_pose(const MotionLibrary& lib, const PlaybackState& s, Pose& out) {
  motion_library_sample(lib, s.segment, s.frame, s.segment_start, s.incoming_transition, out);
}

}  // namespace foresight

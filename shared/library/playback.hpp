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

/// The playing segment's start turned by `turn` (rad) about where the root stands now: root
/// steering's rotation of the motion (LookaheadAvatar), the segment playing on from there.
inline Placement playback_turned_start(const MotionLibrary& lib, const PlaybackState& s, float turn) {
  const Placement now = playback_root(lib, s);
  return {now.pos_m + rotate_ground(s.segment_start.pos_m - now.pos_m, turn), s.segment_start.heading_rad + turn};
}

/// The current pose (pelvis in world space).
inline void playback_pose(const MotionLibrary& lib, const PlaybackState& s, Pose& out) {
  motion_library_sample(lib, s.segment, s.frame, s.segment_start, s.incoming_transition, out);
}

}  // namespace foresight

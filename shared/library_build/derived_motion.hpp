#pragma once
// What a captured library lacks for look-ahead steering, derived from its own frames.
//
// Capture sessions record walks, turns and runs, rarely a standing idle, turns on the spot or
// stops; without them the feasible motion tree has nothing to do once a wall is near, and the
// avatar freezes (issue 16: 3-8 m walked in 60 s). So, at library build time:
//  * a standing pose: the capture's stillest upright frame (pelvis and both ankles slowest), the
//    most compact of those (the idle's body disc must fit wherever the avatar stops);
//  * an idle loop: that pose held for half a second (`derived_idle`);
//  * turns on the spot, both ways, 45 / 90 / 135 degrees: the standing pose turned about the
//    pelvis, eased in and out, in two steps with the feet planted (the foot on the turning side
//    steps to its place in the new facing, then the other; two-bone leg IK keeps a foot on the
//    ground exactly where it is);
//  * a stop from every walking segment's end: the walk plays on while its ground speed and turn
//    rate ease to zero and the pose blends into the standing pose over half a second;
//  * starts into walking segments: the reverse, from the standing pose into the walk's own
//    frames, speed easing up to the walk's;
//  * sharper walking turns: every walking piece that goes nearly straight, bent 40 degrees left
//    and right (its ground path turns at a constant rate, the poses stay the capture's, so the
//    feet slide a little, as under root steering).
// Each derived clip joins the graph where its first or last pose is the pose it joins (a 4-frame
// blend takes up the ground placement's rounding), so every walking clip can be stopped and
// started, and the graph's largest strongly connected component keeps clips the automatic
// transitions alone would lose.
#include "anim/clip.hpp"
#include "graph/motion_graph.hpp"

#include <string>
#include <vector>

namespace foresight {

struct DerivedMotionReport {
  /// What the capture itself has (detected from its root tracks): a stand of a second or more
  /// (under 0.15 m/s, under 10 degrees), a turn on the spot (travelling under 0.3 m/s, 30 degrees
  /// or more within a second or a shorter clip), a stop or a start (between 0.8 m/s and under
  /// 0.15 m/s within 1.5 s).
  bool captured_idle = false, captured_turn_on_spot = false, captured_stop = false, captured_start = false;
  std::string standing_clip;      ///< Where the standing pose comes from.
  int standing_frame = -1;
  float standing_speed_m_per_s = 0.0f;  ///< Pelvis ground speed there (0: perfectly still).
  int idles = 0, turns = 0, stops = 0, starts = 0, bends = 0;
};

/// Appends the derived clips to `clips` (and their tags to `tags`) and their segments and
/// transitions to `graph` (finalised again). `graph` holds the captured clips' segments.
void derive_steering_motion(const Skeleton& skeleton, std::vector<Clip>& clips,
                            std::vector<uint32_t>& tags, MotionGraph& graph,
                            DerivedMotionReport& report);

}  // namespace foresight

#pragma once
// What a library's own motion allows a shown pose (filled by motion_library_compile). A pop is a
// shown frame whose largest joint acceleration exceeds the library's own 99.9th percentile
// (docs/MOTION_QUALITY.md); root steering turns the playing motion about the root and adds
// acceleration to every moving joint, so it turns each frame only as fast as that frame's room
// under the threshold allows (MotionLibrary::steer_limit_rad).
#include "library/motion_library.hpp"

namespace foresight {

/// Steering's rotation adds about 2 x (its rate) x (a joint's speed) to the joint's acceleration
/// (the Coriolis term of a turning frame); per clip frame, the fastest turn that keeps every
/// joint's own acceleration plus that within this share of the pop threshold is the frame's
/// limit (the whole threshold: about as many pops on the built-in library, three times as many
/// on the Bandai capture's maze; docs/MOTION_QUALITY.md, "Steering within the clips' room").
inline constexpr float kSteerBudgetShare = 0.9f;
/// Rad per clip frame: steering may always turn this much (a sixth of 540 deg/s at 30 fps), so a
/// fast motion is never unsteerable...
inline constexpr float kSteerLimitFloor_rad = 0.052f;
/// ...and its limit changes by at most this much from one frame to the next (the turn slows down
/// before a frame with little room instead of stopping dead at it: that stop popped knees too).
inline constexpr float kSteerLimitRamp_rad = 0.105f;

/// Fills lib.frame_acceleration_m, lib.pop_threshold_m and lib.steer_limit_rad from its clips.
void compute_pop_budget(MotionLibrary& lib);

}  // namespace foresight

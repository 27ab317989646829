#pragma once
// An AvatarState from a snapshot, checked against our own copy of the motion library and turned
// into the PlaybackState it describes. Snapshot contents are wire data: a segment, frame or
// transition the library does not have is rejected here, before any library lookup.
#include "foresight_generated.h"
#include "library/playback.hpp"

namespace foresight::protocol {

/// False when the state names a segment, frame or transition outside `library` (or a transition
/// that does not lead into the segment).
bool avatar_playback(const MotionLibrary& library, const wire::AvatarState& state,
                     PlaybackState& out);

/// Where the avatar stands now: a terrain avatar (kAvatarTerrain) says it outright, the others by
/// their playback. False when a playback state is invalid for `library`.
bool avatar_root(const MotionLibrary& library, const wire::AvatarState& state, Placement& out);

}  // namespace foresight::protocol

#pragma once
// Snapshot avatars are wire data: each is checked against our own copy of the motion library
// before anything looks it up (a segment, frame or transition it does not have is rejected).
#include "foresight_generated.h"
#include "snapshot_buffer.hpp"

#include <span>
#include <vector>

namespace foresight::client {

/// False when `state` names a segment, frame or transition outside `library`.
bool avatar_entry_from_wire(const MotionLibrary& library, const wire::AvatarState& state,
                            AvatarEntry& out);
/// Every valid avatar of `avatars` into `out` (cleared first; no allocation once large enough),
/// terrain avatars left out (their bodies come apart: terrain_poses.hpp). Returns how many were
/// rejected.
int avatar_entries_from_wire(const MotionLibrary& library, std::span<const wire::AvatarState> avatars,
                             std::vector<AvatarEntry>& out);

}  // namespace foresight::client

#pragma once
// Does a body fit where it must stand (a spawn, a start)? A scene validates its spawn points as
// points; only with a library is the body known. The answer says what is in the way and how much
// room the body lacks, so a level designer can move the spawn by that much.
#include "library/motion_library.hpp"
#include "world/collision_world.hpp"
#include "world/scene.hpp"

#include <string>

namespace foresight {

/// Empty when every frame of `segment` placed at `at` is free (segment_feasible); otherwise why:
/// outside the bounds, the ground under it, or the box it overlaps and by how much (the room the
/// body lacks), e.g. "the idle body (0.65 m across) overlaps wall 'outer-west' by 0.08 m".
std::string body_fit_problem(const MotionLibrary& library, const Scene& scene, const CollisionWorld& world,
                             int segment, const Placement& at);

}  // namespace foresight

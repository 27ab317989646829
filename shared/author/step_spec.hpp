#pragma once
// One-step clips: the unit of locomotion. A step goes from one family boundary to the next; in it
// one foot (the stance foot) stays on the floor while the other (the stepping foot) swings to its
// next footprint. Between moving families the stepping foot is the end family's lead foot, so a
// step from a right-strike boundary is a left step ending in a left strike, and vice versa.
//
// The stance foot is never moved, so it fixes where the step ends (family_boundary.hpp:
// pinned_end): a walking step is as long as its families make it, and a turning walk step turns by
// pivoting the stance foot on its ball while its heel is up (the rear foot at the end boundary).
// Events near a boundary (the rear foot's heel roll and lift-off, the weight coming onto the
// landing foot) follow the family's timings in seconds, so the pose and the next few frames agree
// whichever clip of the family comes next.
#include "author/gait.hpp"

#include <string>

namespace foresight::author {

/// Timings of the stepping foot where a family does not fix them.
struct StepTiming {
  /// From a standing family: when the stepping foot's heel rises and when it lifts off. Lift-off
  /// at least 0.12 s in, so the weight has left the foot by then.
  float heel_off_s = 0.0f;
  float lift_s = 0.15f;
  /// Into a standing family: when the stepping foot touches down (< 0: the end family's
  /// weight_accept_s before the end, so the weight is on both feet at the boundary).
  float land_s = -1.0f;
};

/// Pass as both speeds for a steady step: the root moves at the step's arc length over its
/// duration.
inline constexpr float kSteadySpeed = -1.0f;

/// A step from family `from` to family `to` (at least one of them moving) that turns by turn_rad
/// (ignored into a standing family: the planted foot fixes the heading there), with the root path's
/// speeds at both ends.
LocomotionSpec step_spec(const std::string& name, uint32_t tags, FamilyId from, FamilyId to,
                         float duration_s, float turn_rad, float start_speed_mps,
                         float end_speed_mps, const FootGeometry& geometry, StepTiming timing = {});

/// The foot that steps in step_spec(from, to).
int stepping_side(FamilyId from, FamilyId to);

}  // namespace foresight::author

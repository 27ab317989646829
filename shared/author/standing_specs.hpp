#pragma once
// Clips between standing families (idle, crouch idle, fighting stance): loops, moves in which each
// foot steps from its start spot to its end spot (crouching down, side-steps, into the stance),
// and turns on the spot made of several small steps.
#include "author/gait.hpp"

#include <span>
#include <string>

namespace foresight::author {

/// A standing loop of a standing family (both feet planted throughout).
LocomotionSpec standing_spec(const std::string& name, uint32_t tags, FamilyId family,
                             float duration_s, StandingMotion motion, const FootGeometry& geometry);

/// A clip between two standing families made of single steps: each foot starts on its start
/// spot and ends on its end spot (relative to `end`); set_step then says when each foot moves.
LocomotionSpec transition_spec(const std::string& name, uint32_t tags, FamilyId start,
                               FamilyId end_family, float duration_s, Placement end,
                               const FootGeometry& geometry);
/// Times one step of `side` in a transition_spec: the heel roll and lift-off from its first plant
/// (< 0: keep the family's) and the touch-down on its last plant.
void set_step(LocomotionSpec& spec, int side, float heel_off_s, float lift_s, float land_s);

/// One step of a turn on the spot: `side` lifts, and lands on its spot of the root turned by
/// `turn_fraction` of the whole turn.
struct SpotStep {
  int side = 0;
  float heel_off_s = 0.0f;
  float lift_s = 0.0f;
  float land_s = 0.0f;
  float turn_fraction = 1.0f;
};

/// A turn on the spot by turn_rad (positive: left; pi is a half turn to the left) in a standing
/// family. The root stays where it is and turns smoothly over the clip; the feet step round in the
/// given order (each foot's last step must land on turn_fraction 1) and stay flat while down.
LocomotionSpec spot_turn_spec(const std::string& name, uint32_t tags, FamilyId family,
                              float duration_s, float turn_rad, std::span<const SpotStep> steps,
                              const FootGeometry& geometry);

}  // namespace foresight::author

#pragma once
// Where the feet are at a family boundary. A boundary pose is defined relative to the root
// placement, so every clip that starts or ends in a family builds its boundary feet from these
// functions and the poses agree by construction.
//
// Moving family placed at `root`, boundary at time t: the lead foot (family.lead_side) touches down
// flat at t; the other foot is either still planted behind, its heel rolling up (walks), or in the
// air on its way forward (runs). Standing family: both feet planted at the family's spots.
#include "author/gait_style.hpp"

namespace foresight::author {

/// A plant of the family's straight, steady cycle `cycle_offset` cycles after the boundary's lead
/// plant (0: that plant; -0.5: the other foot's plant before it; 0.5: its plant after), touching
/// down at land_s, with the family's stance and heel-roll timings.
FootPlant neutral_plant(const GaitFamily& family, int side, const Placement& root, float land_s,
                        float cycle_offset);

/// The other (non-lead) foot's plant before a moving family's boundary at t_s: at the boundary
/// it is still on the floor (walks) or has left it (runs: the boundary key is a via after it).
FootPlant rear_plant(const GaitFamily& family, const Placement& root, float t_s);

/// The foot key covering a family boundary at time t_s, for a root placed at `root`: a plant
/// (moving families: the far event times at their steady values for the caller to override) or a
/// via for a foot caught mid-swing.
FootKey boundary_key(const GaitFamily& family, int side, const Placement& root, float t_s,
                     const FootGeometry& geometry);

/// The end placement of a step whose foot `side` stays on the floor from the start (`planted`,
/// world = the step's start frame) into the end family's boundary. Walks: the foot ends as the
/// rear foot rolling on its ball, which has not moved; it may have pivoted, so the end heading is
/// `turn_rad`. Runs: the foot's last plant is the end family's rear plant (heading `turn_rad`).
/// Standing: the foot stands flat on its spot, unpivoted, which also fixes the heading.
Placement pinned_end(const GaitFamily& to, int side, const FootPlant& planted, float turn_rad,
                     const FootGeometry& geometry);

}  // namespace foresight::author

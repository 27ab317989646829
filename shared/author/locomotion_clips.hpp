#pragma once
// The default locomotion catalogue: standing loops, single steps of every gait on either foot
// (straight and turning), the steps that join gaits, starts and stops, side-steps and turns on the
// spot; each a parameter set for the one gait generator (gait.hpp). Clip names end in the stepping
// foot: walk_l is a left step from a right-foot strike to a left-foot strike.
#include "author/gait.hpp"

#include <vector>

namespace foresight::author {

std::vector<LocomotionSpec> default_locomotion_specs(const FootGeometry& geometry);

}  // namespace foresight::author

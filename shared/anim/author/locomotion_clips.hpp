#pragma once
// The default locomotion catalogue: idle, walks, turns, run, crouch, side-steps and the clips that
// join their families, each a parameter set for the one gait generator (gait.hpp).
#include "anim/author/gait.hpp"

#include <vector>

namespace foresight::author {

std::vector<LocomotionSpec> default_locomotion_specs(const FootGeometry& geometry);

}  // namespace foresight::author

#include "world/terrain.hpp"

#include <algorithm>

namespace foresight {

bool terrain_height_at(const Terrain& terrain, vec2 p_m, float& height_m) {
  return terrain_height_over_steps(
      terrain, p_m, static_cast<int>(terrain.steps.size()),
      [&](int k) -> const StepBlock& { return terrain.steps[static_cast<size_t>(k)]; }, height_m);
}

}  // namespace foresight

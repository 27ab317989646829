#include "world/terrain.hpp"

#include <algorithm>

namespace foresight {

bool terrain_height_at(const Terrain& terrain, vec2 p_m, float& height_m) {
  float h = terrain.floor_y_m;
  bool has_ground = true;
  switch (height_field_sample(terrain.height_field, p_m, h)) {
    case FieldSample::kOutside: h = terrain.floor_y_m; break;
    case FieldSample::kHole: has_ground = false; break;
    case FieldSample::kGround: break;
  }
  // A step over a hole is a bridge: it provides ground on its own.
  for (const StepBlock& step : terrain.steps) {
    if (!step_covers(step, p_m)) continue;
    h = has_ground ? std::max(h, step.max_m.y) : step.max_m.y;
    has_ground = true;
  }
  if (has_ground) height_m = h;
  return has_ground;
}

}  // namespace foresight

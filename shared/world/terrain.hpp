#pragma once
// Ground height queries on a Terrain (scene.hpp): the exact reference that the compiled collision
// world agrees with, and what scene validation uses to put spawns on the ground.
#include "world/scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace foresight {

enum class FieldSample : std::uint8_t {
  kOutside,  ///< p is not over the field (the floor applies there).
  kHole,     ///< p is over a hole: no ground.
  kGround,   ///< p is over a cell with a height.
};

/// The height-field cell containing p. Cells are half-open,
/// [origin + i * cell, origin + (i + 1) * cell), so the field covers
/// [origin, origin + count * cell) on each axis. NaN coordinates give kOutside.
inline FieldSample height_field_sample(const HeightField& field, vec2 p_m, float& height_m) {
  if (field.empty()) return FieldSample::kOutside;
  const float fx = (p_m.x - field.origin_m.x) / field.cell_m;
  const float fz = (p_m.y - field.origin_m.y) / field.cell_m;
  // Written so that NaN fails the test.
  if (!(fx >= 0.0f && fx < static_cast<float>(field.count_x) && fz >= 0.0f &&
        fz < static_cast<float>(field.count_z)))
    return FieldSample::kOutside;
  const int ix = static_cast<int>(fx), iz = static_cast<int>(fz);
  const float h = field.heights_m[static_cast<std::size_t>(iz) * field.count_x + ix];
  if (std::isnan(h)) return FieldSample::kHole;
  height_m = h;
  return FieldSample::kGround;
}

/// True when p lies on the step's top (closed rectangle).
inline bool step_covers(const StepBlock& step, vec2 p_m) {
  return p_m.x >= step.min_m.x && p_m.x <= step.max_m.x && p_m.y >= step.min_m.z &&
         p_m.y <= step.max_m.z;
}

/// Ground height at p: the base (the height field where it covers p, else the floor) raised to the
/// top of every step block covering p. False where there is no ground (a height-field hole with no
/// step over it). Does not look at scene bounds. Cost: O(number of steps).
bool terrain_height_at(const Terrain& terrain, vec2 p_m, float& height_m);

/// terrain_height_at over a subset of the steps: `step_at(k)` for k in [0, num_steps) returns the
/// k-th candidate step (e.g. only those registered near a grid cell; the others must not cover p).
template <typename StepAt>
bool terrain_height_over_steps(const Terrain& terrain, vec2 p_m, int num_steps, StepAt step_at,
                               float& height_m) {
  float h = terrain.floor_y_m;
  bool has_ground = true;
  switch (height_field_sample(terrain.height_field, p_m, h)) {
    case FieldSample::kOutside: h = terrain.floor_y_m; break;
    case FieldSample::kHole: has_ground = false; break;
    case FieldSample::kGround: break;
  }
  // A step over a hole is a bridge: it provides ground on its own.
  for (int k = 0; k < num_steps; ++k) {
    const StepBlock& step = step_at(k);
    if (!step_covers(step, p_m)) continue;
    h = has_ground ? std::max(h, step.max_m.y) : step.max_m.y;
    has_ground = true;
  }
  if (has_ground) height_m = h;
  return has_ground;
}

}  // namespace foresight

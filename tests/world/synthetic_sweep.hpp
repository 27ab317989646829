#pragma once
// Synthetic per-frame body volumes for the world tests (independent of any motion library): a cylinder
// or capsule (long axis along the path) moving along a straight line or a circular arc from the origin, starting toward +Z
// (segment-local space, as make_segment_shape expects).
#include "world/body_volume.hpp"

#include <vector>

namespace foresight {

struct SyntheticSweepSpec {
  int frames = 30;
  float forward_m = 1.2f;   ///< Path length travelled by the disc centre.
  float turn_rad = 0.0f;    ///< Total heading change along the path (+ = toward +X, the left).
  float sideways_m = 0.0f;  ///< Extra straight drift toward +X over the segment (side steps).
  float radius_m = 0.35f;
  float half_length_m = 0.0f;  ///< Capsule core half length along the path's heading (0: a disc).
  float y_min_m = 0.0f;
  float y_max_m = 1.85f;
};

/// Walking: 30 frames, 1.2 m forward, y 0..1.85, radius 0.35 (the defaults).
inline SyntheticSweepSpec synthetic_walk() { return {}; }
/// Crouch-walking: as walking but y 0..1.08.
inline SyntheticSweepSpec synthetic_crouch_walk() {
  SyntheticSweepSpec s;
  s.y_max_m = 1.08f;
  return s;
}

/// Frame i at t = i / (frames - 1) along the path (frame 0 at the origin).
std::vector<BodyVolume> synthetic_sweep(const SyntheticSweepSpec& spec);

}  // namespace foresight

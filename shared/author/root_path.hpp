#pragma once
// The ground path a locomotion clip follows: where the character's root frame (a point between the
// feet plus a heading) is at each time. A cubic Hermite curve from the origin (heading 0) to an end
// placement, with the start/end speeds as tangents, so clips chained at their boundaries keep
// their speed. Footprints are laid on this path.
#include "author/key_track.hpp"
#include "math/types.hpp"

#include <utility>

namespace foresight::author {

class RootPath {
 public:
  RootPath() = default;
  /// `end`: placement at duration_s relative to the start. Turning paths bulge like a circular arc
  /// of the same turn (cubic arc approximation), straight paths move at constant speed when the
  /// two speeds agree with the distance.
  RootPath(float duration_s, Placement end, float start_speed_mps, float end_speed_mps);

  /// Replaces the eased heading by a keyed one (turns on the spot: the body follows the feet).
  /// Its first and last keys must be 0 and end().heading_rad.
  void set_heading(KeyTrack<float> heading) { heading_ = std::move(heading); }

  Placement at(float t_s) const;
  float duration_s() const { return duration_s_; }
  const Placement& end() const { return end_; }

 private:
  float duration_s_ = 1.0f;
  Placement end_;
  vec2 start_tangent_{0.0f}, end_tangent_{0.0f};  // per unit of normalised time
  KeyTrack<float> heading_;                        // empty: eased from 0 to end_.heading_rad
};

}  // namespace foresight::author

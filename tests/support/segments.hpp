#pragma once
// Segments of a motion library that tests root trees and avatars in.
#include "library/motion_library.hpp"

namespace foresight::test {

/// A walking segment (moves forward at least 0.3 m), so a tree rooted in it has children at once;
/// segment 0 when the library has none.
inline int walk_segment(const MotionLibrary& lib) {
  for (int s = 0; s < lib.graph.num_segments(); ++s) {
    const uint32_t tags = lib.graph.segments[s].tags;
    if ((tags & kTagLocomotion) && !(tags & (kTagCrouch | kTagRun | kTagTurn)) &&
        lib.segment_motion[s].end.pos_m.y > 0.3f)
      return s;
  }
  return 0;
}

}  // namespace foresight::test

#pragma once
// The motion graph: nodes are clip segments (frame ranges), edges are feasible transitions with a
// blend length. Transitions are stored sorted by source segment with offsets (CSR), so the
// successors of a segment are one contiguous span.
#include "math/types.hpp"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace foresight {

/// What a segment does, for planners and the client (bit flags).
enum SegmentTag : uint32_t {
  kTagNone = 0,
  kTagIdle = 1u << 0,
  kTagLocomotion = 1u << 1,
  kTagCrouch = 1u << 2,
  kTagFight = 1u << 3,
  kTagTurn = 1u << 4,
  kTagRun = 1u << 5,
  /// Short repositioning steps (a half step forward): a fighter's footwork to close in on its
  /// target. Players' trees leave them out (MotionTreeConfig::excluded_tags).
  kTagFootwork = 1u << 6,
};

struct Segment {
  std::string name;
  int clip = -1;
  int first_frame = 0;  ///< First frame played.
  int end_frame = 0;    ///< One past the last frame played; the successor starts where this would be.
  uint32_t tags = kTagNone;
  int num_frames() const { return end_frame - first_frame; }
};

struct Transition {
  int from = -1;
  int to = -1;
  int blend_frames = 0;  ///< Frames over which `to` is blended from the end of `from`.
};

struct MotionGraph {
  std::vector<Segment> segments;
  std::vector<Transition> transitions;  ///< Sorted by `from` (then `to`): see finalize().
  std::vector<int> first_transition;    ///< segments.size() + 1 offsets into transitions.

  int num_segments() const { return static_cast<int>(segments.size()); }
  std::span<const Transition> successors(int segment) const {
    return {transitions.data() + first_transition[segment],
            static_cast<size_t>(first_transition[segment + 1] - first_transition[segment])};
  }
  /// Sorts transitions, drops duplicates and rebuilds the offsets. Call after editing.
  void finalize();
  /// Index of the segment called `name`, or -1.
  int find_segment(std::string_view name) const;
};

}  // namespace foresight

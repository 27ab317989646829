#include "library/motion_library.hpp"

#include <algorithm>
#include <cassert>

namespace foresight {

int MotionLibrary::find_transition(int from, int to) const {
  const auto succ = graph.successors(from);
  for (size_t i = 0; i < succ.size(); ++i)
    if (succ[i].to == to) return graph.first_transition[from] + static_cast<int>(i);
  return -1;
}

SegmentBody segment_body(const MotionLibrary& lib, int segment) {
  SegmentBody b;
  for (const BodyVolume& v : lib.volumes(segment)) {
    b.width_m = std::max(b.width_m, 2.0f * v.radius_m);
    b.length_m = std::max(b.length_m, 2.0f * v.reach_m());
    b.height_m = std::max(b.height_m, v.y_max_m - v.y_min_m);
  }
  return b;
}

float lowest_moving_body_m(const MotionLibrary& library) {
  float lowest = kStandingHeight_m;
  bool any = false;
  for (int s = 0; s < library.graph.num_segments(); ++s) {
    if (!(library.graph.segments[s].tags & kTagLocomotion)) continue;
    const float top = library.segment_shapes[static_cast<size_t>(s)].y_max_m;
    lowest = any ? std::min(lowest, top) : top;
    any = true;
  }
  return lowest;
}

float moving_body_clearance_m(const MotionLibrary& library) {
  std::vector<float> widths;
  for (int s = 0; s < library.graph.num_segments(); ++s)
    if (library.graph.segments[s].tags & kTagLocomotion) widths.push_back(segment_body(library, s).width_m);
  if (widths.empty()) return 0.35f;
  std::nth_element(widths.begin(), widths.begin() + static_cast<std::ptrdiff_t>(widths.size() / 2), widths.end());
  return 0.5f * widths[widths.size() / 2] + kMovingBodySteerRoom_m;
}

Placement motion_library_root_at(const MotionLibrary& lib, int segment, int frame,
                                 const Placement& segment_start) {
  const Segment& s = lib.graph.segments[segment];
  const Placement local = lib.segment_motion[segment].start.inverse().compose(
      lib.root_placement(s.clip, s.first_frame + frame));
  return segment_start.compose(local);
}

void motion_library_sample(const MotionLibrary& lib, int segment, int frame,
                           const Placement& segment_start, int incoming_transition, Pose& out) {
  const Segment& s = lib.graph.segments[segment];
  assert(frame >= 0 && frame <= s.num_frames());
  const int clip_frame = s.first_frame + frame;
  const Placement from = lib.root_placement(s.clip, clip_frame);
  const Placement to = motion_library_root_at(lib, segment, frame, segment_start);
  pose_from_clip(lib.clips[s.clip], clip_frame, from, to, out);
  if (incoming_transition < 0) return;
  const Transition& t = lib.graph.transitions[incoming_transition];
  assert(t.to == segment);
  const float w = blend_out_weight(frame, t.blend_frames);
  if (w <= 0.0f) return;
  // The offset lives in the compiled arrays; view it without copying.
  const size_t n = static_cast<size_t>(lib.num_joints());
  const PoseOffsetView view{{lib.transition_offset_pos_m.data() + incoming_transition * n, n},
                            {lib.transition_offset_rot.data() + incoming_transition * n, n}};
  pose_apply_offset(view, w, to, out);
}

}  // namespace foresight

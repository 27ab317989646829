#include "protocol/avatar_state.hpp"

#include "protocol/protocol.hpp"
#include "protocol/quantize.hpp"

namespace foresight::protocol {

bool avatar_playback(const MotionLibrary& library, const wire::AvatarState& state,
                     PlaybackState& out) {
  const auto& graph = library.graph;
  const int segment = state.segment();
  if (segment >= static_cast<int>(graph.segments.size())) return false;
  // motion_library_sample takes frames up to num_frames inclusive (the end frame).
  const int frame = state.frame();
  if (frame > graph.segments[static_cast<size_t>(segment)].num_frames()) return false;
  const int transition = state.transition();
  if (transition < -1 || transition >= static_cast<int>(graph.transitions.size())) return false;
  if (transition >= 0 && graph.transitions[static_cast<size_t>(transition)].to != segment) return false;
  out.segment = segment;
  out.frame = frame;
  out.incoming_transition = transition;
  out.segment_start.pos_m = vec2(protocol::dequantize_mm(state.start_x_mm()),
                                 protocol::dequantize_mm(state.start_z_mm()));
  out.segment_start.heading_rad = protocol::dequantize_angle(state.start_heading());
  return true;
}

bool avatar_root(const MotionLibrary& library, const wire::AvatarState& state, Placement& out) {
  if (state.flags() & kAvatarTerrain) {
    out = {vec2(dequantize_mm(state.start_x_mm()), dequantize_mm(state.start_z_mm())),
           dequantize_angle(state.start_heading())};
    return true;
  }
  PlaybackState playback;
  if (!avatar_playback(library, state, playback)) return false;
  out = playback_root(library, playback);
  return true;
}

}  // namespace foresight::protocol

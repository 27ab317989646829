#include "graph_build/declared_graph.hpp"

namespace foresight {

bool graph_from_declared(std::span<const Clip> clips, std::span<const uint32_t> clip_tags,
                         std::span<const DeclaredTransition> transitions, MotionGraph& out,
                         std::string& error) {
  out = MotionGraph{};
  for (size_t c = 0; c < clips.size(); ++c) {
    if (clips[c].num_frames < 2) return error = "clip '" + clips[c].name + "' has < 2 frames", false;
    out.segments.push_back({clips[c].name, static_cast<int>(c), 0, clips[c].num_frames - 1,
                            c < clip_tags.size() ? clip_tags[c] : kTagNone});
  }
  for (size_t i = 0; i < transitions.size(); ++i) {
    const DeclaredTransition& t = transitions[i];
    const int from = out.find_segment(t.from), to = out.find_segment(t.to);
    if (from < 0 || to < 0)
      return error = "transition " + std::to_string(i) + " (" + t.from + " -> " + t.to +
                     "): unknown clip '" + (from < 0 ? t.from : t.to) + "'",
             false;
    if (t.blend_frames < 0)
      return error = "transition " + std::to_string(i) + ": negative blend_frames", false;
    out.transitions.push_back({from, to, t.blend_frames});
  }
  out.finalize();
  return true;
}

}  // namespace foresight

#pragma once
// Builder 1: the graph a motion library declares in its manifest. Every clip is one segment
// (it plays frames [0, N-1); frame N-1 is the boundary pose its successors start from).
#include "anim/clip.hpp"
#include "graph/motion_graph.hpp"

#include <span>
#include <string>

namespace foresight {

struct DeclaredTransition {
  std::string from;  ///< Clip name.
  std::string to;    ///< Clip name.
  int blend_frames = 0;
};

/// Returns false with a reason naming the transition when a clip name is unknown or a clip
/// has fewer than 2 frames.
bool graph_from_declared(std::span<const Clip> clips, std::span<const uint32_t> clip_tags,
                         std::span<const DeclaredTransition> transitions, MotionGraph& out,
                         std::string& error);

}  // namespace foresight

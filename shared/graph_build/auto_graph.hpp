#pragma once
// Builder 2: the automatic motion graph of Kovar, Gleicher and Pighin, "Motion Graphs" (2002).
//   1. Frame-to-frame distance: the joint positions of a window of frames after frame i of clip A
//      and after frame j of clip B form two point clouds; their distance is the sum of squared
//      distances under the ground-plane rigid alignment (rotation about Y + translation in XZ)
//      that minimises it (closed form).
//   2. Transition points: local minima of that distance over (i, j) below a threshold.
//   3. Clips are split at the transition points into segments; consecutive segments of a clip
//      stay linked; each transition becomes an edge blended over the window.
//   4. The graph is pruned to its largest strongly connected component (no dead ends).
// Beyond the paper: clip joins. Windows look after a cut, so a clip's last frames never lead
// anywhere; where clip A's last pose, carried on one frame at its last velocity, matches clip B's
// first two frames (same alignment, same threshold), A's end continues into B's start. Takes cut
// into cycles or single moves (walk_l then walk_r) then chain.
#include "anim/clip.hpp"
#include "graph/motion_graph.hpp"

#include <span>
#include <string>

namespace foresight {

/// Frames over which a clip join is blended (the poses already match within the threshold).
inline constexpr int kClipJoinBlendFrames = 4;

struct AutoGraphOptions {
  int window_frames = 10;        ///< Frames compared and blended (1/3 s at 30 fps). [Limit: >= 2]
  int window_stride = 2;         ///< Use every n-th frame of the window in the point cloud.
  int candidate_stride = 2;      ///< Compare every n-th frame as a transition point. [Limit: >= 1]
  float threshold_rms_m = 0.07f; ///< Max RMS point distance (metres) of an accepted transition.
  int min_segment_frames = 10;   ///< No cut closer than this to another cut of the same clip.
  /// Joints in the point cloud: a joint is used if its name contains one of these (case-sensitive);
  /// empty = every joint that is not an End Site.
  std::vector<std::string> joint_filter;
  /// Step 4. Off: every segment stays (a caller that adds its own transitions prunes after).
  bool prune_to_largest_component = true;
};

struct AutoGraphReport {
  long long frame_pairs_compared = 0;
  int local_minima = 0;            ///< Below threshold, before cut-spacing rules.
  int transitions_accepted = 0;    ///< Cross-clip or in-clip jumps added before pruning.
  int clip_joins = 0;              ///< Ends continued into starts (header comment).
  int segments_before_prune = 0;
  int edges_before_prune = 0;
  int segments = 0;                ///< In the largest strongly connected component.
  int edges = 0;
};

/// Builds the graph over `clips` (all on `skeleton`'s topology, normalised, same fps).
/// Returns false with a reason if there are no clips, the fps differ, or nothing is connected.
bool graph_build_automatic(const Skeleton& skeleton, std::span<const Clip> clips,
                           const AutoGraphOptions& options, MotionGraph& out,
                           AutoGraphReport* report, std::string& error);

}  // namespace foresight

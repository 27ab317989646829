#pragma once
// Whole-graph operations shared by the builders.
#include "graph/motion_graph.hpp"

#include <vector>

namespace foresight {

/// Segments of the largest strongly connected component (ascending). Segments outside it are dead
/// ends or unreachable: an avatar entering them could get stuck, so Kovar et al. prune them.
std::vector<int> largest_strongly_connected_component(const MotionGraph& graph);

/// The graph restricted to `keep` (ascending segment indices), reindexed, transitions between kept
/// segments only. finalize() is called on the result.
MotionGraph graph_keep_segments(const MotionGraph& graph, const std::vector<int>& keep);

/// Every segment longer than `max_frames` cut into equal consecutive pieces of at most that many
/// frames ("name@first" each), linked in order without a blend: transitions into a segment now
/// enter its first piece, transitions out of it leave its last. Shorter segments mean more
/// frequent decisions (a player's command is answered sooner, a wall is met with a choice).
/// finalize() is called on the result.
MotionGraph graph_split_long_segments(const MotionGraph& graph, int max_frames);

}  // namespace foresight

#pragma once
// Strategy 3's priorities: how often each child of a segment was chosen in recorded navigation
// (paper 5.2, "statistic data of how the children of a node are chosen"), as a probability per
// transition, learned from the transitions an avatar took while a training recording was replayed.
#include "graph/motion_graph.hpp"

#include <span>
#include <vector>

namespace foresight {

struct TransitionStatistics {
  /// Per transition index of the graph: P(child | parent) in (0, 1). Empty = not learned.
  std::vector<float> probability;
  bool empty() const { return probability.empty(); }
};

/// Counts the transitions taken (indices into graph.transitions) and turns the counts into
/// per-parent probabilities with additive smoothing (`smoothing` pseudo-counts per child), so an
/// unseen child keeps a small, non-zero priority. Out-of-range indices are ignored.
TransitionStatistics transition_statistics_learn(const MotionGraph& graph,
                                                 std::span<const int> transitions_taken,
                                                 float smoothing = 0.5f);

}  // namespace foresight

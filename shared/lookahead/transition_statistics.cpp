#include "lookahead/transition_statistics.hpp"

namespace foresight {

TransitionStatistics transition_statistics_learn(const MotionGraph& graph,
                                                 std::span<const int> transitions_taken,
                                                 float smoothing) {
  const int num_transitions = static_cast<int>(graph.transitions.size());
  std::vector<float> count(static_cast<size_t>(num_transitions), smoothing);
  for (int t : transitions_taken)
    if (t >= 0 && t < num_transitions) count[static_cast<size_t>(t)] += 1.0f;
  TransitionStatistics out;
  out.probability.resize(static_cast<size_t>(num_transitions));
  for (int s = 0; s < graph.num_segments(); ++s) {
    const int first = graph.first_transition[s], last = graph.first_transition[s + 1];
    float total = 0.0f;
    for (int t = first; t < last; ++t) total += count[static_cast<size_t>(t)];
    for (int t = first; t < last; ++t)
      out.probability[static_cast<size_t>(t)] = total > 0 ? count[static_cast<size_t>(t)] / total : 0.0f;
  }
  return out;
}

}  // namespace foresight

#include "graph/motion_graph.hpp"

#include <algorithm>

namespace foresight {

void MotionGraph::finalize() {
  std::sort(transitions.begin(), transitions.end(), [](const Transition& a, const Transition& b) {
    return a.from != b.from ? a.from < b.from : a.to < b.to;
  });
  transitions.erase(std::unique(transitions.begin(), transitions.end(),
                                [](const Transition& a, const Transition& b) {
                                  return a.from == b.from && a.to == b.to;
                                }),
                    transitions.end());
  first_transition.assign(segments.size() + 1, 0);
  for (const Transition& t : transitions) ++first_transition[static_cast<size_t>(t.from) + 1];
  for (size_t i = 1; i < first_transition.size(); ++i) first_transition[i] += first_transition[i - 1];
}

int MotionGraph::find_segment(std::string_view name) const {
  for (size_t i = 0; i < segments.size(); ++i)
    if (segments[i].name == name) return static_cast<int>(i);
  return -1;
}

}  // namespace foresight

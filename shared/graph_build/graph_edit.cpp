#include "graph_build/graph_edit.hpp"

#include <algorithm>
#include <string>

namespace foresight {

std::vector<int> largest_strongly_connected_component(const MotionGraph& graph) {
  // Tarjan's algorithm, iterative so a long chain of segments cannot overflow the stack.
  const int n = graph.num_segments();
  std::vector<int> index(static_cast<size_t>(n), -1), low(static_cast<size_t>(n), 0);
  std::vector<int> component(static_cast<size_t>(n), -1);
  std::vector<char> on_stack(static_cast<size_t>(n), 0);
  std::vector<int> stack;
  std::vector<std::pair<int, int>> call;  // (segment, next successor position)
  int next_index = 0, num_components = 0;
  for (int root = 0; root < n; ++root) {
    if (index[root] >= 0) continue;
    call.push_back({root, 0});
    while (!call.empty()) {
      auto& [v, pos] = call.back();
      if (pos == 0 && index[v] < 0) {
        index[v] = low[v] = next_index++;
        stack.push_back(v);
        on_stack[v] = 1;
      }
      const auto succ = graph.successors(v);
      if (pos < static_cast<int>(succ.size())) {
        const int w = succ[static_cast<size_t>(pos++)].to;
        if (index[w] < 0) {
          call.push_back({w, 0});
        } else if (on_stack[w]) {
          low[v] = std::min(low[v], index[w]);
        }
        continue;
      }
      if (low[v] == index[v]) {
        int w;
        do {
          w = stack.back();
          stack.pop_back();
          on_stack[w] = 0;
          component[w] = num_components;
        } while (w != v);
        ++num_components;
      }
      const int finished = v;
      call.pop_back();
      if (!call.empty()) low[call.back().first] = std::min(low[call.back().first], low[finished]);
    }
  }
  std::vector<int> size(static_cast<size_t>(num_components), 0);
  for (int c : component) ++size[static_cast<size_t>(c)];
  const int best = static_cast<int>(std::max_element(size.begin(), size.end()) - size.begin());
  std::vector<int> keep;
  for (int v = 0; v < n; ++v)
    if (component[v] == best) keep.push_back(v);
  return keep;
}

MotionGraph graph_keep_segments(const MotionGraph& graph, const std::vector<int>& keep) {
  std::vector<int> new_index(graph.segments.size(), -1);
  MotionGraph out;
  for (int old : keep) {
    new_index[old] = static_cast<int>(out.segments.size());
    out.segments.push_back(graph.segments[old]);
  }
  for (const Transition& t : graph.transitions)
    if (new_index[t.from] >= 0 && new_index[t.to] >= 0)
      out.transitions.push_back({new_index[t.from], new_index[t.to], t.blend_frames});
  out.finalize();
  return out;
}

MotionGraph graph_split_long_segments(const MotionGraph& graph, int max_frames) {
  MotionGraph out;
  std::vector<int> first_piece(graph.segments.size()), last_piece(graph.segments.size());
  for (size_t s = 0; s < graph.segments.size(); ++s) {
    const Segment& seg = graph.segments[s];
    const int pieces = max_frames > 0 ? std::max(1, (seg.num_frames() + max_frames - 1) / max_frames) : 1;
    first_piece[s] = out.num_segments();
    for (int k = 0; k < pieces; ++k) {
      Segment piece = seg;
      piece.first_frame = seg.first_frame + seg.num_frames() * k / pieces;
      piece.end_frame = seg.first_frame + seg.num_frames() * (k + 1) / pieces;
      if (k > 0) {
        const size_t at = seg.name.rfind('@');
        piece.name = (at == std::string::npos ? seg.name : seg.name.substr(0, at)) + "@" + std::to_string(piece.first_frame);
        out.transitions.push_back({out.num_segments() - 1, out.num_segments(), 0});
      }
      out.segments.push_back(piece);
    }
    last_piece[s] = out.num_segments() - 1;
  }
  for (const Transition& t : graph.transitions)
    out.transitions.push_back({last_piece[static_cast<size_t>(t.from)], first_piece[static_cast<size_t>(t.to)], t.blend_frames});
  out.finalize();
  return out;
}

}  // namespace foresight

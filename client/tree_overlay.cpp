#include "tree_overlay.hpp"

#include <algorithm>

namespace foresight::client {

namespace {

constexpr float kTreeLineM = 0.06f, kChosenLineM = 0.12f;
/// A square outline (side) around each chosen node's end: idle clips end where they start, and
/// the choice still shows around a standing avatar's feet.
constexpr float kChosenMarkM = 0.60f;
constexpr float kTreeLiftM = 0.06f;  ///< Above the floor, so the floor never hides the lines.

/// The graph transition from `from` to `to` (the graph keeps at most one per pair), or -1.
int transition_between(const MotionGraph& graph, int from, int to) {
  if (from < 0 || from >= graph.num_segments()) return -1;
  const auto successors = graph.successors(from);
  for (size_t k = 0; k < successors.size(); ++k)
    if (successors[k].to == to) return graph.first_transition[static_cast<size_t>(from)] + static_cast<int>(k);
  return -1;
}

}  // namespace

void tree_ghost_states(const MotionLibrary& library, const protocol::TreeView& tree,
                       std::vector<PlaybackState>& out) {
  out.clear();
  const MotionGraph& graph = library.graph;
  for (size_t i = 0; i < tree.size(); ++i) {
    if (!tree.chosen[i] || tree.parent[i] == protocol::kTreeNoParent) continue;
    const int segment = tree.segment[i];
    if (segment >= graph.num_segments()) continue;  // not in our library: nothing to rebuild
    PlaybackState s;
    s.segment = segment;
    s.segment_start = tree.start(i);
    s.incoming_transition = transition_between(graph, tree.segment[tree.parent[i]], segment);
    const int frames = graph.segments[static_cast<size_t>(segment)].num_frames();
    const int mid = std::max(frames / 2, 0), last = std::max(frames - 1, 0);
    s.frame = mid;
    out.push_back(s);
    if (last != mid) {
      s.frame = last;
      out.push_back(s);
    }
  }
}

void add_tree_overlay(Renderer& renderer, const MotionLibrary& library, const protocol::TreeView& tree,
                      float floor_y_m, std::vector<PlaybackState>& ghosts) {
  const float y = floor_y_m + kTreeLiftM;
  const auto at = [y](vec2 ground) { return vec3(ground.x, y, ground.y); };
  for (int pass = 0; pass < 2; ++pass) {
    for (size_t i = 0; i < tree.size(); ++i) {
      if ((tree.chosen[i] != 0) != (pass == 1)) continue;
      renderer.add_line(at(tree.start(i).pos_m), at(tree.end_m[i]), pass == 1 ? kChosenLineM : kTreeLineM,
                        pass == 1 ? kChosenColour : kTreeColour);
      if (pass == 1) {  // a square outline around the end
        const vec3 c = at(tree.end_m[i]);
        const float h = 0.5f * kChosenMarkM;
        const vec3 corners[4] = {c + vec3(-h, 0, -h), c + vec3(h, 0, -h), c + vec3(h, 0, h), c + vec3(-h, 0, h)};
        for (int k = 0; k < 4; ++k) renderer.add_line(corners[k], corners[(k + 1) % 4], kTreeLineM, kChosenColour);
      }
    }
  }
  tree_ghost_states(library, tree, ghosts);
  for (const PlaybackState& s : ghosts) renderer.add_avatar(library, s, 0.0f, kGhostColour, AvatarStyle::kGhost);
}

}  // namespace foresight::client

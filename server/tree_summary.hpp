#pragma once
// The TreeSummary a player gets on TreeRequest (schema/foresight.fbs, docs/PROTOCOL.md): a compact
// sample of its own feasible motion tree for the client's overlay (paper Fig. 5).
//
// Sampled, at most protocol::kMaxTreeSamples nodes: the root, then the chosen branch (the root's
// child MotionTree::select_child() would take now, then recursively the child with the largest
// weighted branch sum), then the remaining nodes breadth-first by depth. Every sampled node's
// parent is sampled before it, so the client can draw each one as a line from its parent's end.
//
// Memory: the scratch buffers are sized to the tree's node pool on first use and reused: once
// warm, writing a summary allocates nothing.
#include "lookahead/motion_tree.hpp"
#include "protocol/packet.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace foresight::server {

class TreeSummaryWriter {
 public:
  /// Builds the summary of `tree` (non-const only because select_child() brings stale priorities
  /// up to date, as the next grow() would) into `w`. The bytes stay valid until w's next begin().
  std::span<const uint8_t> write(protocol::PacketWriter& w, MotionTree& tree, uint32_t tick,
                                 uint32_t avatar_id);

  /// The samples of the last write() (for tests and tools).
  std::span<const wire::TreeNodeSample> samples() const { return samples_; }

 private:
  bool add(const MotionTree& tree, int node, vec2 origin);

  std::vector<wire::TreeNodeSample> samples_;
  std::vector<int32_t> sample_of_;  ///< Per pool index: its sample index, -1 when not sampled.
  std::vector<float> branch_sum_;   ///< Per pool index: weighted sum of its subtree.
  std::vector<int32_t> preorder_;   ///< The tree's nodes, depth-first from the root.
  std::vector<int32_t> queue_;      ///< Breadth-first scratch.
};

}  // namespace foresight::server

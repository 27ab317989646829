#include "tree_summary.hpp"

#include "protocol/protocol.hpp"
#include "protocol/quantize.hpp"

#include <algorithm>
#include <cmath>

namespace foresight::server {

namespace {

int16_t to_cm16(float metres) {
  const float cm = std::round(metres * 100.0f);
  return static_cast<int16_t>(std::clamp(cm, -32767.0f, 32767.0f));
}

}  // namespace

bool TreeSummaryWriter::add(const MotionTree& tree, int node, vec2 origin) {
  if (samples_.size() >= protocol::kMaxTreeSamples) return false;
  const size_t ni = static_cast<size_t>(node);
  if (sample_of_[ni] >= 0) return true;
  const MotionTreeNode& n = tree.node(node);
  const int32_t parent_sample = n.parent >= 0 ? sample_of_[static_cast<size_t>(n.parent)] : -1;
  const uint16_t parent = parent_sample >= 0 ? static_cast<uint16_t>(parent_sample) : protocol::kTreeNoParent;
  const int depth = static_cast<int>(n.depth) - static_cast<int>(tree.node(tree.root()).depth);
  sample_of_[ni] = static_cast<int32_t>(samples_.size());
  // Segment and start heading let the client rebuild the node's clip (ghost poses); its start
  // position is its parent's end, already on the wire.
  samples_.emplace_back(to_cm16(n.end.pos_m.x - origin.x), to_cm16(n.end.pos_m.y - origin.y), parent,
                        static_cast<uint8_t>(std::clamp(depth, 0, 255)), uint8_t{0},
                        static_cast<uint16_t>(std::clamp(tree.segment_of(node), 0, 0xFFFF)),
                        protocol::quantize_angle(tree.start_of(node).heading_rad));
  return true;
}

std::span<const uint8_t> TreeSummaryWriter::write(protocol::PacketWriter& w, MotionTree& tree,
                                                  uint32_t tick, uint32_t avatar_id) {
  samples_.clear();
  preorder_.clear();
  const int root = tree.root();
  vec2 origin(0.0f), chosen_end(0.0f);
  if (root >= 0) {
    const int chosen = tree.select_child();  // first: it refreshes stale priorities
    const size_t pool = static_cast<size_t>(tree.node_capacity());
    if (sample_of_.size() < pool) {
      sample_of_.assign(pool, -1);
      branch_sum_.assign(pool, 0.0f);
      preorder_.reserve(pool);
      queue_.reserve(pool);
      samples_.reserve(protocol::kMaxTreeSamples);
    }
    const MotionTreeNode& r = tree.node(root);
    origin = chosen_end = tree.start_of(root).pos_m;

    // Weighted branch sums (section 4.3), bottom-up over the depth-first order.
    const auto& weights = tree.config().selection_weights;
    tree.for_each_node([&](int index, const MotionTreeNode& n) {
      preorder_.push_back(index);
      const int below = static_cast<int>(n.depth) - static_cast<int>(r.depth);
      branch_sum_[static_cast<size_t>(index)] =
          below <= 0 ? 0.0f : weights[std::min(static_cast<size_t>(below - 1), weights.size() - 1)] * n.match;
    });
    for (auto it = preorder_.rbegin(); it != preorder_.rend(); ++it) {
      const MotionTreeNode& n = tree.node(*it);
      if (*it != root && n.parent >= 0)
        branch_sum_[static_cast<size_t>(n.parent)] += branch_sum_[static_cast<size_t>(*it)];
    }

    // The root, the chosen branch, then breadth-first.
    add(tree, root, origin);
    if (chosen >= 0) chosen_end = tree.node(chosen).end.pos_m;
    for (int c = chosen; c >= 0;) {
      if (!add(tree, c, origin)) break;
      samples_[static_cast<size_t>(sample_of_[static_cast<size_t>(c)])].mutate_flags(protocol::kTreeNodeChosen);
      int best = -1;
      float best_sum = -1.0f;
      for (int k = tree.node(c).first_child; k >= 0; k = tree.node(k).next_sibling) {
        if (branch_sum_[static_cast<size_t>(k)] > best_sum) {
          best = k;
          best_sum = branch_sum_[static_cast<size_t>(k)];
        }
      }
      c = best;
    }
    queue_.clear();
    queue_.push_back(root);
    for (size_t head = 0; head < queue_.size() && samples_.size() < protocol::kMaxTreeSamples; ++head) {
      for (int k = tree.node(queue_[head]).first_child; k >= 0; k = tree.node(k).next_sibling) {
        if (!add(tree, k, origin)) break;
        queue_.push_back(k);
      }
    }
    // Leave the per-pool scratch clean for the next request (only the touched entries).
    for (const int32_t index : preorder_) sample_of_[static_cast<size_t>(index)] = -1;
  }

  auto& fbb = w.begin();
  const auto sampled = fbb.CreateVectorOfStructs(samples_.data(), samples_.size());
  wire::TreeSummaryBuilder b(fbb);
  b.add_tick(tick);
  b.add_avatar(avatar_id);
  b.add_nodes(static_cast<uint32_t>(std::max(tree.num_nodes(), 0)));
  b.add_chosen_child_end_x_mm(protocol::quantize_mm(chosen_end.x));
  b.add_chosen_child_end_z_mm(protocol::quantize_mm(chosen_end.y));
  b.add_origin_x_mm(protocol::quantize_mm(origin.x));
  b.add_origin_z_mm(protocol::quantize_mm(origin.y));
  b.add_sampled(sampled);
  return w.finish(b.Finish());
}

}  // namespace foresight::server

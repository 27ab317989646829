#include "lookahead/motion_tree.hpp"

#include <algorithm>
#include <cassert>
#include <utility>

namespace foresight {

namespace {

// Per-thread scratch (capacity kept): trees are worked on by one thread at a time, and keeping
// these per tree cost every avatar ~10 KB.
struct RankedChild {
  int64_t sum;  ///< RootChildSum::sum.
  int node;     ///< Also the creation order (ties go to the earlier child).
};
thread_local std::vector<RankedChild> t_ranked;
thread_local std::vector<std::pair<int, int>> t_branch_stack;  // refresh_priorities: node, root_sums_ slot
thread_local std::vector<int32_t> t_new_index;                 // compact(): old index -> new
thread_local std::vector<int> t_walk_stack;

}  // namespace

std::vector<int>& MotionTree::walk_stack() { return t_walk_stack; }

MotionTree::MotionTree(const MotionLibrary& library, const CollisionWorld& world,
                       MotionTreeConfig config)
    : library_(library), world_(world), config_(std::move(config)) {
  config_.max_nodes = std::clamp(config_.max_nodes, 2, kMaxTreeNodes);
  config_.max_depth = std::clamp(config_.max_depth, 1, 255);
  if (config_.node_pool == nullptr) own_pool_ = std::make_unique<MotionNodePool>();
  pool_ = config_.node_pool != nullptr ? config_.node_pool : own_pool_.get();
  ranked_nodes_.reserve(64);  // a segment's successors; grows once if a graph has more
  root_sums_.reserve(64);
  if (!library_.clips.empty()) segment_fps_ = library_.clips.front().fps;
  reset(0, Placement{});
}

MotionTree::~MotionTree() { give_back_chunks_from(0); }

void MotionTree::give_back_chunks_from(size_t first) {
  if (first >= chunks_.size()) return;
  pool_->give_back(std::span(chunks_).subspan(first));
  chunks_.resize(first);
}

void MotionTree::reset(int segment, const Placement& start, int incoming_transition) {
  // Nothing survives a reset. The tree keeps the chunks it had filled (it is likely to grow as
  // far again: steering resets a tree every steered frame) and gives back the rest.
  if (config_.compact_on_reroot)
    give_back_chunks_from(static_cast<size_t>(std::max(1, chunks_for(first_unused_))));
  priorities_stale_ = false;
  root_sums_.clear();  // the root alone: no branches
  sums_valid_ = true;
  first_unused_ = 0;  // O(1)
  num_nodes_ = 0;
  queue_.clear();
  root_ = allocate();
  root_start_ = start;
  root_segment_ = segment;
  MotionTreeNode& r = at(root_);
  r.end = start.compose(library_.segment_motion[static_cast<size_t>(segment)].end);
  r.transition = incoming_transition;
  r.grow_priority = 1.0f;
  r.match = 1.0f;
  queue_.push_back({r.grow_priority, root_});
}

// After a re-root (root_ is the new root), the nodes reached from it move down to indices
// 0..n-1 in the order they had, so index order stays creation order (ties are broken by it) and
// the tree holds no freed node; the chunks past them go back to the pool. Depths drop by one
// (they are relative to the root, so the depth cap keeps looking the same distance ahead).
// O(nodes allocated since the last re-root), once per re-root. In place: a node only moves down,
// to a slot whose node has already moved or is dead.
void MotionTree::compact() {
  std::vector<int32_t>& new_index = t_new_index;
  new_index.assign(static_cast<size_t>(first_unused_), -1);
  for_each_node([&](int n, const MotionTreeNode&) { new_index[static_cast<size_t>(n)] = 0; });
  int count = 0;
  for (int32_t& i : new_index)
    if (i == 0) i = count++;
  const auto renumber = [&](int16_t i) { return i < 0 ? i : static_cast<int16_t>(new_index[static_cast<size_t>(i)]); };
  for (int i = 0; i < first_unused_; ++i) {
    const int to = new_index[static_cast<size_t>(i)];
    if (to < 0) continue;
    MotionTreeNode n = at(i);
    n.parent = renumber(n.parent);
    n.first_child = renumber(n.first_child);
    n.next_sibling = renumber(n.next_sibling);
    --n.depth;
    at(to) = n;
  }
  root_ = new_index[static_cast<size_t>(root_)];
  first_unused_ = count;
  num_nodes_ = count;
  give_back_chunks_from(static_cast<size_t>(chunks_for(count)));
  // The leaf queue and the branch sums named old indices: advance_root left them stale, and they
  // are rebuilt from the tree before their next use. A queue far larger than the tree is cut.
  assert(priorities_stale_ && !sums_valid_);
  queue_.clear();
  if (queue_.capacity() > 2 * static_cast<size_t>(count) + 64) {
    std::vector<QueueEntry> smaller;
    smaller.reserve(static_cast<size_t>(count) + 64);
    queue_.swap(smaller);
  }
  root_sums_.clear();
}

int MotionTree::allocate() {
  assert(first_unused_ < config_.max_nodes);
  // One chunk more when the budget pays for more nodes than the tree holds (once per 64 nodes,
  // never per node); chunks never move, so references into other chunks stay valid.
  if (first_unused_ == node_capacity()) chunks_.push_back(pool_->take());
  const int i = first_unused_++;
  at(i) = MotionTreeNode{};
  ++num_nodes_;
  return i;
}

// Command matching (4.2): the angle between the command u and v_k, the movement from where the
// avatar stands now to where node k ends, mapped to (0, 1) by g(a) = (1 + cos a) / 2. Two soft
// terms beyond the paper, each in [0.5, 1]: facing (the node ends facing the command) and pace
// (the segment moves at walking pace or faster). Without them a library with side-steps,
// starts and stops matches a command as well by strafing or stop-and-go as by turning and
// walking, because direction alone cannot tell them apart.
// A zero command means "stop": nodes that end close to the avatar, facing the way it faces, match
// best (without the heading term turning on the spot matches "stop" as well as standing still,
// and an idle avatar fidgets round in circles).
float MotionTree::base_match(const MotionTreeNode& n, int segment, const Placement& start) const {
  const SegmentMotion& motion = library_.segment_motion[static_cast<size_t>(segment)];
  const vec2 v = n.end.pos_m - avatar_.pos_m;
  const float v_len = glm::length(v);
  const float end_heading = start.heading_rad + motion.end.heading_rad;
  float g;
  if (command_ == vec2(0.0f)) {
    const float turn = std::abs(wrap_angle(end_heading - avatar_.heading_rad));
    g = (1.0f - std::min(v_len / 2.0f, 1.0f)) * (1.0f - 0.8f * turn / kPi);
  } else if (v_len < 1e-3f) {
    g = 0.25f;  // standing still while asked to move: a poor but not impossible match
  } else {
    const float direction = 0.5f * (1.0f + glm::dot(command_, v) / v_len);
    const vec2 facing(std::sin(end_heading), std::cos(end_heading));
    const float facing_match = 0.75f + 0.25f * glm::dot(command_, facing);
    const int frames = library_.graph.segments[static_cast<size_t>(segment)].num_frames();
    const float speed_mps = glm::length(motion.end.pos_m) * segment_fps_ / static_cast<float>(frames);
    const float pace = 0.5f + 0.5f * std::min(speed_mps / kWalkingPace_mps, 1.0f);
    g = direction * facing_match * pace;
  }
  if (crouch_ && !(library_.graph.segments[static_cast<size_t>(segment)].tags & kTagCrouch))
    g *= kStandingWhileCrouchHeld;
  return std::clamp(g, config_.min_priority, config_.max_priority);
}

float MotionTree::statistic(const MotionTreeNode& n) const {
  if (statistics_.empty() || n.transition < 0) return 0.5f;
  return std::clamp(statistics_.probability[static_cast<size_t>(n.transition)],
                    config_.min_priority, config_.max_priority);
}

float MotionTree::grow_priority_of(const MotionTreeNode& n, int segment, const Placement& start,
                                   float parent_grow) const {
  switch (config_.strategy) {
    case Strategy::kBreadthFirst: return -static_cast<float>(n.depth);
    case Strategy::kCommand:
    case Strategy::kCommandNoResort: return n.match;
    case Strategy::kStatistic: return parent_grow * statistic(n);
    case Strategy::kHybrid: return parent_grow * base_match(n, segment, start) * statistic(n);
  }
  return 0.0f;
}

void MotionTree::set_command(vec2 world_direction, const Placement& avatar, bool crouch) {
  const float len = glm::length(world_direction);
  const vec2 command = len > 1e-4f && std::isfinite(len) ? world_direction / len : vec2(0.0f);
  // The same command from the same place matches every node as it does now (the server re-sorts
  // periodically; a standing avatar's full tree would be walked twice for nothing).
  if (matches_current_ && crouch == crouch_ && command == command_ && avatar.pos_m == avatar_.pos_m &&
      avatar.heading_rad == avatar_.heading_rad)
    return;
  matches_current_ = true;
  crouch_ = crouch;
  command_ = command;
  avatar_ = avatar;
  command_changed_ = true;
}

// The walk is a recomputation from the root under the command and placement kept, so doing it
// when the tree is next used gives what doing it in set_command() and after every change since
// would have given.
void MotionTree::update_priorities_if_stale() {
  if (!priorities_stale_ && !command_changed_) return;
  refresh_priorities();
  // Strategies that keep the priorities nodes were created with keep their queue too, unless
  // the queue itself is stale (advance_root).
  if (priorities_stale_ || config_.strategy == Strategy::kCommand || config_.strategy == Strategy::kHybrid)
    rebuild_queue();
  priorities_stale_ = false;
  command_changed_ = false;
}

void MotionTree::refresh_priorities() {
  const bool resort = config_.strategy == Strategy::kCommand || config_.strategy == Strategy::kHybrid;
  const auto& w = config_.selection_weights;
  // Depth-first from the root visits every parent before its children; the same pass sums each
  // of the root's branches again (4.3).
  root_sums_.clear();
  std::vector<std::pair<int, int>>& branch_stack = t_branch_stack;
  branch_stack.clear();
  branch_stack.push_back({root_, -1});
  while (!branch_stack.empty()) {
    const auto [index, slot_in] = branch_stack.back();
    branch_stack.pop_back();
    MotionTreeNode& node = at(index);
    int slot = slot_in;
    if (node.parent < 0) {
      node.match = 1.0f;
      if (resort) node.grow_priority = 1.0f;
    } else {
      const MotionTreeNode& p = at(node.parent);
      const int segment = library_.graph.transitions[static_cast<size_t>(node.transition)].to;
      node.match = p.match * base_match(node, segment, p.end);
      if (resort) node.grow_priority = grow_priority_of(node, segment, p.end, p.grow_priority);
      if (slot < 0) {  // a child of the root: its own branch
        slot = static_cast<int>(root_sums_.size());
        root_sums_.push_back({index, 0});
      }
      root_sums_[static_cast<size_t>(slot)].sum += branch_weight(w, node);
    }
    for (int c = node.first_child; c >= 0; c = at(c).next_sibling) branch_stack.push_back({c, slot});
  }
  sums_valid_ = true;
}

void MotionTree::rebuild_queue() {
  queue_.clear();
  for_each_node([&](int index, const MotionTreeNode& n) {
    if (!n.expanded && n.depth < config_.max_depth)
      queue_.push_back({n.grow_priority, index});
  });
  std::make_heap(queue_.begin(), queue_.end(), queue_less);
}

GrowResult MotionTree::grow(const GrowBudget& budget) {
  update_priorities_if_stale();
  const auto& w = config_.selection_weights;
  GrowResult result;
  const bool has_deadline = budget.deadline != std::chrono::steady_clock::time_point::max();
  while (true) {
    if (queue_.empty()) {
      result.status |= kGrowExhausted;
      break;
    }
    if (result.expansions >= budget.max_expansions ||
        (has_deadline && std::chrono::steady_clock::now() >= budget.deadline)) {
      result.status |= kGrowBudgetSpent;
      break;
    }
    const QueueEntry best = queue_.front();
    const int leaf_segment = segment_of(best.node);
    const auto successors = library_.graph.successors(leaf_segment);
    // Expand a leaf whole or not at all, so a full pool never leaves it half expanded.
    if (static_cast<int>(successors.size()) > config_.max_nodes - first_unused_) {
      result.status |= kGrowOutOfNodes;
      break;
    }
    std::pop_heap(queue_.begin(), queue_.end(), queue_less);
    queue_.pop_back();

    const int leaf_index = best.node;
    const int branch_slot = sums_valid_ ? branch_slot_of(leaf_index) : -1;  // where its children's weights add
    const Placement place = at(leaf_index).end;  // where every child starts
    const int first_transition = library_.graph.first_transition[static_cast<size_t>(leaf_segment)];
    for (size_t i = 0; i < successors.size(); ++i) {
      const int segment = successors[i].to;
      if (library_.graph.segments[static_cast<size_t>(segment)].tags & config_.excluded_tags) continue;
      ++result.expansions;
      CheckStats stats;
      const bool feasible = !config_.check_collisions ||
                            segment_feasible(world_, library_.segment_shapes[segment], place, &stats);
      result.frame_checks += static_cast<int64_t>(stats.frame_checks);
      if (!feasible) continue;
      const int child = allocate();
      MotionTreeNode& parent = at(leaf_index);
      MotionTreeNode& c = at(child);
      c.end = place.compose(library_.segment_motion[static_cast<size_t>(segment)].end);
      c.transition = first_transition + static_cast<int>(i);
      c.parent = static_cast<int16_t>(leaf_index);
      c.depth = static_cast<uint8_t>(parent.depth + 1);
      c.match = parent.match * base_match(c, segment, place);
      c.grow_priority = grow_priority_of(c, segment, place, parent.grow_priority);
      c.next_sibling = parent.first_child;
      parent.first_child = static_cast<int16_t>(child);
      ++result.nodes_added;
      if (sums_valid_) {
        const int64_t weighted = branch_weight(w, c);
        if (branch_slot < 0) root_sums_.push_back({child, weighted});  // a new child of the root
        else root_sums_[static_cast<size_t>(branch_slot)].sum += weighted;
      }
      if (c.depth < config_.max_depth) {
        queue_.push_back({c.grow_priority, child});
        std::push_heap(queue_.begin(), queue_.end(), queue_less);
      }
    }
    at(leaf_index).expanded = 1;
  }
  return result;
}

// One node's share of its branch sum (4.3): its match weighted by its depth below the root, in
// fixed point (2^-32), so that a sum is the same whatever order its nodes are added in (grow
// adds them one by one; refresh_priorities all at once) and the ranking never depends on it.
int64_t MotionTree::branch_weight(const std::array<float, 8>& w, const MotionTreeNode& n) {
  const double weighted = static_cast<double>(w[std::min(static_cast<size_t>(n.depth - 1), w.size() - 1)]) * n.match;
  return static_cast<int64_t>(std::llround(weighted * 4294967296.0));
}

// The root_sums_ entry of the root's child whose branch holds `index` (-1 for the root itself).
int MotionTree::branch_slot_of(int index) const {
  if (index == root_) return -1;
  while (at(index).parent != root_) index = at(index).parent;
  for (size_t i = 0; i < root_sums_.size(); ++i)
    if (root_sums_[i].node == index) return static_cast<int>(i);
  assert(false && "every child of the root has a branch sum");
  return -1;
}

std::span<const int> MotionTree::ranked_children() {
  // Branch sums (4.3): every node of a child's branch, weighted by its depth below the root,
  // summed as the nodes come (grow) and all again whenever every match or depth changes
  // (refresh_priorities): ranking is then a sort of the root's few children, every frame.
  update_priorities_if_stale();
  assert(sums_valid_ && "only advance_root() invalidates them, and it leaves the priorities stale");
  std::vector<RankedChild>& ranked = t_ranked;
  ranked.clear();
  for (const RootChildSum& r : root_sums_) ranked.push_back({r.sum, r.node});
  std::sort(ranked.begin(), ranked.end(), [](const RankedChild& a, const RankedChild& b) {
    return a.sum > b.sum || (a.sum == b.sum && a.node < b.node);
  });
  ranked_nodes_.clear();
  for (const RankedChild& r : ranked) ranked_nodes_.push_back(r.node);
  return ranked_nodes_;
}

int MotionTree::select_child(const ChildVeto* veto) {
  // The veto (a reservation check of every frame, on the server) is asked best first, so only
  // the children better than the one taken are checked.
  for (const int c : ranked_children()) {
    if (veto == nullptr || !veto->blocks(segment_of(c), start_of(c))) return c;
  }
  return -1;
}

int MotionTree::advance_root(int child) {
  assert(child >= 0 && at(child).parent == root_);
  const int transition = at(child).transition;
  root_start_ = at(root_).end;
  root_segment_ = segment_of(child);
  at(root_).first_child = -1;  // the old root and the branches not taken are no longer reached
  root_ = child;
  MotionTreeNode& r = at(root_);
  r.parent = -1;
  r.next_sibling = -1;
  priorities_stale_ = true;
  sums_valid_ = false;
  if (config_.compact_on_reroot) {
    compact();
  } else {
    num_nodes_ = 0;
    for_each_node([&](int index, const MotionTreeNode&) {
      --at(index).depth;
      ++num_nodes_;
    });
  }
  return transition;
}

int MotionTree::max_depth_reached() const {
  int d = 0;
  for_each_node([&](int, const MotionTreeNode& n) { d = std::max(d, static_cast<int>(n.depth)); });
  return d;
}

}  // namespace foresight

#pragma once
// The feasible motion tree (paper section 4): a best-first look-ahead over the motion graph.
//
// A node is (segment, placement of the avatar root when the segment starts). The root is the
// segment now playing. Growing takes the best leaf, places every successor segment at the leaf's
// end, keeps the collision-free ones (every frame checked) and gives them priorities. When the
// playing segment ends, advance_root() picks the child whose branch has the largest weighted sum
// of priorities (4.3); the root moves down and the sibling subtrees are freed (Fig. 4).
//
// Memory: nodes live in chunks of 64 taken from a MotionNodePool (one shared by every avatar of a
// server, or the tree's own), allocated in index order, and the leaf queue is a heap over a
// vector. A tree takes a chunk when its budget pays for more nodes than it holds, up to
// max_nodes; at every re-root the live nodes move down to indices 0..n-1 in the order they had
// (compact()) and the chunks past them go back to the pool; a reset keeps only the chunks the
// tree had filled. So the trees' memory follows the nodes their budgets pay for, summed over the
// avatars, with no free list and no holes. Nothing is allocated per node: a chunk per 64 nodes.
// Determinism: the same inputs and the same expansion budget give the same tree, bit for bit
// (ties are broken by the order nodes were created, which is their index order).
#include "library/motion_library.hpp"
#include "lookahead/motion_node_pool.hpp"
#include "lookahead/motion_tree_node.hpp"
#include "lookahead/strategy.hpp"
#include "lookahead/transition_statistics.hpp"
#include "world/collision_check.hpp"
#include "world/collision_world.hpp"

#include <array>
#include <chrono>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace foresight {

struct MotionTreeConfig {
  int max_nodes = 8192;        ///< Nodes at most (the tree's storage grows to this). [2, kMaxTreeNodes]
  /// Where the tree's node chunks come from: the server's pool, shared by its avatars. nullptr:
  /// the tree makes its own (tests, benches, one avatar alone).
  MotionNodePool* node_pool = nullptr;
  /// false: a re-root leaves the freed nodes where they are (never reused, so the tree fills up)
  /// and keeps every chunk. Only for a test that compares a tree that compacts with one that
  /// does not.
  bool compact_on_reroot = true;
  int max_depth = 8;           ///< Root is depth 0; nodes deeper than this are never created. [1, 255]
  Strategy strategy = Strategy::kCommand;
  /// Weight of a node at depth d (1-based below the root) in the branch sum of 4.3; decreasing.
  /// Depths past the end use the last weight.
  std::array<float, 8> selection_weights{1.0f, 0.5f, 0.25f, 0.125f, 0.0625f, 0.03125f, 0.015625f,
                                         0.0078125f};
  /// Base priorities are clamped to [min_priority, max_priority] so 0 < pb < 1 as in the paper.
  float min_priority = 0.01f;
  float max_priority = 0.99f;
  /// false: children are kept without a collision check. Only for the naive baseline controller
  /// (a game FSM that plays the best-matching clip and stops when it would collide), never for
  /// look-ahead.
  bool check_collisions = true;
  /// Segments with any of these tags are never added: a player steering with arrow keys does not
  /// mean to throw punches (SegmentTag bits, graph/motion_graph.hpp). Nor to shuffle half steps:
  /// offered to players, they changed their closed-loop runs for the worse (docs/MOTION_QUALITY.md,
  /// "A start that sets off"); fighters take them (server_fighters.cpp).
  uint32_t excluded_tags = kTagFight | kTagFootwork;
  /// Steering mode (0: off, the paper's controller), applied by LookaheadAvatar while a direction
  /// is held: a playing locomotion segment is rotated about the avatar's root towards the command
  /// by at most this much per second (if the rotated segment is collision-free and leaves a way
  /// on; the tree then regrows from it), a segment whose rest goes nowhere (a standing loop, a
  /// stop's settling) is left early for a moving child, a moving avatar does not stop while it
  /// can keep moving, and no child that can only stand still afterwards is taken
  /// (docs/LOOKAHEAD.md "Steering mode"). Games turn the root the same way; the feet slide.
  float steer_rad_per_s = 0.0f;
};

/// The paper's controller and the two baselines of the navigation comparison, as tree settings.
inline MotionTreeConfig greedy_depth1_config(MotionTreeConfig c) {
  c.max_depth = 1;
  return c;
}
inline MotionTreeConfig naive_fsm_config(MotionTreeConfig c) {
  c.max_depth = 1;
  c.check_collisions = false;
  c.strategy = Strategy::kCommand;
  return c;
}

/// How much growing may spend: a number of expansions (deterministic tests, experiments) and/or a
/// wall-clock deadline (production). One expansion = one successor placed, collision-checked over
/// all its frames, and prioritised.
struct GrowBudget {
  int64_t max_expansions = INT64_MAX;
  std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max();

  static GrowBudget expansions(int64_t n) { return {n, std::chrono::steady_clock::time_point::max()}; }
  static GrowBudget until(std::chrono::steady_clock::time_point t) { return {INT64_MAX, t}; }
};

/// Why growing stopped (bit flags, Detour-style: the tree is always the best partial answer).
enum GrowStatus : uint32_t {
  kGrowBudgetSpent = 1u << 0,  ///< Expansion count or deadline reached.
  kGrowOutOfNodes = 1u << 1,   ///< The pool is full.
  kGrowExhausted = 1u << 2,    ///< No leaf left to expand (depth cap or dead ends everywhere).
};

struct GrowResult {
  uint32_t status = 0;
  int64_t expansions = 0;    ///< Successors placed and checked.
  int64_t nodes_added = 0;   ///< Of those, the feasible ones kept.
  int64_t frame_checks = 0;  ///< Body frames tested against the scene.
};

/// A last word at decision time on a child the tree would pick (the server vetoes motions that
/// would run into other avatars' committed motion: lookahead/reservations.hpp).
class ChildVeto {
 public:
  virtual bool blocks(int segment, const Placement& start) const = 0;

 protected:
  ~ChildVeto() = default;
};

class MotionTree {
 public:
  MotionTree(const MotionLibrary& library, const CollisionWorld& world, MotionTreeConfig config);
  MotionTree(const MotionTree&) = delete;
  MotionTree& operator=(const MotionTree&) = delete;
  ~MotionTree();  ///< Gives every chunk back to the pool.

  /// Drops every node and makes (segment at start) the root, entered by `incoming_transition`.
  void reset(int segment, const Placement& start, int incoming_transition = -1);

  /// The player's command as a world ground direction (zero = stop) and where the avatar stands
  /// and faces now (v_k is measured from there; "stop" prefers staying and facing the same way).
  /// For re-sorting strategies (command, hybrid) every leaf's priority is recomputed and the queue
  /// rebuilt; breadth-first, command-no-resort and statistic keep the priorities nodes were
  /// created with. The walk that does it (about 25 ns a node) is left to the tree's next
  /// grow(), select_child() or ranked_children(), on whichever thread makes that call: the
  /// server hands every avatar its command before deciding, and only the avatars deciding walk
  /// their trees there; the others walk on the look-ahead threads.
  /// `crouch` (the player's crouch button) makes segments without kTagCrouch a poorer match, so
  /// the avatar crouches where it can and stands where it must.
  void set_command(vec2 world_direction, const Placement& avatar, bool crouch = false);

  /// Switches the exploration strategy at run time: the tree keeps its root (the segment playing)
  /// and regrows under the new priorities.
  void set_strategy(Strategy strategy) {
    config_.strategy = strategy;
    reset(root_segment_, root_start_, at(root_).transition);
  }

  /// Strategy 3 and 4 priorities (learned elsewhere). Without them both fall back to uniform.
  void set_statistics(TransitionStatistics statistics) {
    statistics_ = std::move(statistics);
    matches_current_ = false;  // the next set_command() re-prioritises, even with the same command
  }

  /// Grows best-first until the budget is spent, the pool is full or nothing is left to expand.
  GrowResult grow(const GrowBudget& budget);

  /// The child of the root with the largest weighted branch sum under the current command, or -1
  /// when the root has no feasible child (none that `veto` lets through). Ties go to the earlier
  /// child.
  int select_child(const ChildVeto* veto = nullptr);
  /// The root's children best first by the same ranking (one walk of the tree), for a caller
  /// choosing under several rules at once (LookaheadAvatar::select_child).
  std::span<const int> ranked_children();

  /// Makes `child` (a child of the root) the root and frees every other branch. Returns the graph
  /// transition that enters it. Priorities (products from the root) and the leaf queue are
  /// brought up to date lazily, by the next set_command(), grow() or select_child(): the server
  /// decides for every avatar in one sequential pass and grows them on several threads, and this
  /// puts the re-prioritising on those threads. The result is the same as doing it here.
  /// Node indices held across it are void: the live nodes are renumbered from 0.
  int advance_root(int child);

  int root() const { return root_; }
  const MotionTreeNode& node(int index) const { return at(index); }
  /// The segment node `index` plays: its transition's target (the root's is kept by the tree).
  int segment_of(int index) const {
    return index == root_ ? root_segment_
                          : library_.graph.transitions[static_cast<size_t>(at(index).transition)].to;
  }
  /// Where node `index`'s segment starts: where its parent's ends (the root's is kept by the tree).
  const Placement& start_of(int index) const { return index == root_ ? root_start_ : at(at(index).parent).end; }
  int num_nodes() const { return num_nodes_; }  ///< Live nodes (those reached from the root).
  /// Nodes the tree's chunks hold now (node indices are below it): whole chunks, up to the
  /// chunk that holds config().max_nodes.
  int node_capacity() const { return static_cast<int>(chunks_.size()) * MotionNodePool::kChunkNodes; }
  /// Bytes of node storage the tree holds (its chunks and its leaf queue).
  size_t node_bytes() const {
    return chunks_.size() * sizeof(MotionNodePool::Chunk) + queue_.capacity() * sizeof(QueueEntry);
  }
  int num_leaves_queued() const { return static_cast<int>(queue_.size()); }
  int max_depth_reached() const;
  const MotionTreeConfig& config() const { return config_; }
  Strategy strategy() const { return config_.strategy; }
  /// Bytes of memory per node: the node plus its share of the queue entry.
  static constexpr size_t bytes_per_node() { return sizeof(MotionTreeNode) + sizeof(QueueEntry); }

  /// Visits every node in the tree (depth-first from the root): f(index, node). f may walk this
  /// or another tree too (the walk stack is the thread's, each walk using its own top part).
  template <typename F>
  void for_each_node(F&& f) const {
    if (root_ >= 0) walk_subtree(root_, [&](int n) { f(n, at(n)); });
  }

 private:
  struct QueueEntry {
    float priority;
    int32_t node;
  };
  /// The heap's order: higher priority first; on a tie the node created first (FIFO, for
  /// determinism), which is the lower index.
  static bool queue_less(const QueueEntry& a, const QueueEntry& b) {
    return a.priority != b.priority ? a.priority < b.priority : a.node > b.node;
  }

  /// The calling thread's scratch stack for walks (one per thread, not per tree: a tree is only
  /// ever walked by the thread working on it, and 200 trees need not keep 200 stacks).
  static std::vector<int>& walk_stack();
  /// f(index) for `first` and every node below it, each before its children; f may unlink the
  /// node from its siblings (its children are taken after f returns, its siblings before).
  template <typename F>
  void walk_subtree(int first, F&& f) const {
    std::vector<int>& stack = walk_stack();
    const size_t base = stack.size();
    stack.push_back(first);
    while (stack.size() > base) {
      const int n = stack.back();
      stack.pop_back();
      f(n);
      for (int c = at(n).first_child; c >= 0; c = at(c).next_sibling) stack.push_back(c);
    }
  }
  MotionTreeNode& at(int index) {
    return chunks_[static_cast<size_t>(index) >> MotionNodePool::kChunkShift]
        ->nodes[static_cast<size_t>(index) & (MotionNodePool::kChunkNodes - 1)];
  }
  const MotionTreeNode& at(int index) const {
    return chunks_[static_cast<size_t>(index) >> MotionNodePool::kChunkShift]
        ->nodes[static_cast<size_t>(index) & (MotionNodePool::kChunkNodes - 1)];
  }
  static int chunks_for(int nodes) {
    return (nodes + MotionNodePool::kChunkNodes - 1) / MotionNodePool::kChunkNodes;
  }
  void give_back_chunks_from(size_t first);
  void compact();
  int allocate();
  int branch_slot_of(int index) const;
  static int64_t branch_weight(const std::array<float, 8>& weights, const MotionTreeNode& n);
  /// Node n plays `segment` from `start` (neither is stored in the node).
  float base_match(const MotionTreeNode& n, int segment, const Placement& start) const;
  float statistic(const MotionTreeNode& n) const;
  float grow_priority_of(const MotionTreeNode& n, int segment, const Placement& start, float parent_grow) const;
  void refresh_priorities();  // recompute match (and re-sorting grow priorities) top-down
  void rebuild_queue();
  void update_priorities_if_stale();

  const MotionLibrary& library_;
  const CollisionWorld& world_;
  MotionTreeConfig config_;
  TransitionStatistics statistics_;
  std::unique_ptr<MotionNodePool> own_pool_;  ///< Without config().node_pool.
  MotionNodePool* pool_;
  std::vector<MotionNodePool::Chunk*> chunks_;  ///< Node i is chunks_[i / 64]->nodes[i % 64].
  std::vector<QueueEntry> queue_;
  std::vector<int> ranked_nodes_;    ///< ranked_children()'s result (capacity kept).
  int first_unused_ = 0;  ///< The next node allocated gets this index.
  int num_nodes_ = 0;
  Placement root_start_;  ///< Where the root's segment starts.
  int root_segment_ = 0;
  /// Per child of the root: its branch sum, kept up to date as nodes are added. Valid while
  /// sums_valid_ (advance_root changes every depth: the next refresh_priorities sums again).
  struct RootChildSum {
    int node;
    int64_t sum;  ///< Fixed point: branch_weight().
  };
  std::vector<RootChildSum> root_sums_;
  bool sums_valid_ = false;
  int root_ = -1;
  bool priorities_stale_ = false;  ///< Set by advance_root(), cleared by update_priorities_if_stale().
  bool command_changed_ = false;   ///< Set by set_command(), cleared by update_priorities_if_stale().
  /// set_command() may skip re-prioritising a repeat of the same command and placement.
  bool matches_current_ = false;
  static constexpr float kWalkingPace_mps = 1.2f;  // at or above it a motion gets full pace credit
  vec2 command_{0.0f};
  bool crouch_ = false;
  static constexpr float kStandingWhileCrouchHeld = 0.3f;  // base priority factor
  Placement avatar_;
  float segment_fps_ = 30.0f;
};

}  // namespace foresight

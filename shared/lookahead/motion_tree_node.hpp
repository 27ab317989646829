#pragma once
// One node of the feasible motion tree (lookahead/motion_tree.hpp): a segment placed in the world.
#include "math/types.hpp"

#include <cstdint>

namespace foresight {

/// 32 bytes, no padding (a test compares trees byte for byte); a tree of 800 nodes is 25 KB.
/// What follows from other nodes is not stored: a node starts where its parent ends (the root
/// where MotionTree::start_of() says), its segment is its transition's target (the root's is the
/// tree's), and its creation order is its index (MotionTree allocates in order and keeps that
/// order when it renumbers). Indices, not pointers: a tree renumbers its nodes at every re-root.
/// 16-bit links: a tree holds at most kMaxTreeNodes nodes, -1 is "none" (so
/// `for (int c = n.first_child; c >= 0; ...)` walks).
inline constexpr int kMaxTreeNodes = 32767;
struct MotionTreeNode {
  Placement end;            ///< World placement where the segment ends (its children start there).
  float grow_priority = 0;  ///< Heap key (strategy dependent; breadth-first: -depth).
  float match = 1;          ///< Product of command-matching base priorities from the root.
  int32_t transition = -1;  ///< Graph transition from the parent's segment (the root's may be -1).
  int16_t parent = -1;
  int16_t first_child = -1;
  int16_t next_sibling = -1;
  uint8_t depth = 0;     ///< Below the root; at most MotionTreeConfig::max_depth (255).
  uint8_t expanded = 0;  ///< 1 once its successors were placed.
};
static_assert(sizeof(MotionTreeNode) == 32, "no padding: trees are compared byte for byte");

}  // namespace foresight

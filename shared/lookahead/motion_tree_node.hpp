#pragma once
// One node of the feasible motion tree (lookahead/motion_tree.hpp): a segment placed in the world.
#include "math/types.hpp"

#include <cstdint>

namespace foresight {

/// 48 bytes, no padding (a test compares trees byte for byte). Indices, not pointers: a tree
/// renumbers its nodes when it gives storage back. 16-bit links: a tree holds at most
/// kMaxTreeNodes nodes, -1 is "none" (so `for (int c = n.first_child; c >= 0; ...)` walks).
inline constexpr int kMaxTreeNodes = 32767;
struct MotionTreeNode {
  Placement start;          ///< World placement where the segment starts.
  vec2 end_pos_m{0.0f};     ///< World ground position where it ends (for v_k and drawing).
  float grow_priority = 0;  ///< Heap key (strategy dependent; breadth-first: -depth).
  float match = 1;          ///< Product of command-matching base priorities from the root.
  uint32_t order = 0;       ///< Creation order since the last reset: ties go to the earlier node.
  int32_t segment = -1;
  int32_t transition = -1;  ///< Graph transition from the parent's segment (-1 for the root).
  int16_t parent = -1;
  int16_t first_child = -1;
  int16_t next_sibling = -1;  ///< Also links the free list.
  uint8_t depth = 0;          ///< Below the root; at most MotionTreeConfig::max_depth (255).
  uint8_t expanded = 0;       ///< 1 once its successors were placed.
};
static_assert(sizeof(MotionTreeNode) == 48, "no padding: trees are compared byte for byte");

}  // namespace foresight

#pragma once
// Node storage shared by motion trees (docs/LOOKAHEAD.md "Memory and determinism"): chunks of
// kChunkNodes nodes that a tree takes as its budget pays for nodes and gives back when a re-root
// or a reset leaves it with fewer. One pool serves every avatar of a server, so the memory follows the sum of
// the trees, whose peaks (just before each re-root) come at different times, not each tree's own
// peak. Chunks, not nodes, go through the lock: a tree takes one per 64 nodes it grows by.
// Thread-safe: trees grow on the look-ahead workers.
#include "lookahead/motion_tree_node.hpp"

#include <array>
#include <cstddef>
#include <mutex>
#include <span>
#include <vector>

namespace foresight {

class MotionNodePool {
 public:
  static constexpr int kChunkShift = 6;
  static constexpr int kChunkNodes = 1 << kChunkShift;
  struct Chunk {
    std::array<MotionTreeNode, kChunkNodes> nodes;
  };

  MotionNodePool() = default;
  MotionNodePool(const MotionNodePool&) = delete;
  MotionNodePool& operator=(const MotionNodePool&) = delete;
  ~MotionNodePool();  ///< Every chunk must have been given back (trees die before their pool).

  Chunk* take();
  void give_back(std::span<Chunk* const> chunks);

  /// Bytes of the chunks trees hold now.
  size_t bytes_in_use() const;
  /// Bytes of the chunks kept for trees that grow again.
  size_t bytes_spare() const;

 private:
  /// Spare chunks kept for trees that grow again: at most this many, or a sixteenth of those in use
  /// (more are freed: the pool follows the sum of the trees down as well as up).
  static constexpr size_t kMinSpare = 32;

  mutable std::mutex mutex_;
  std::vector<Chunk*> spare_;
  size_t in_use_ = 0;
};

}  // namespace foresight

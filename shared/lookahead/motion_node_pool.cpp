#include "lookahead/motion_node_pool.hpp"

#include <algorithm>
#include <cassert>

namespace foresight {

MotionNodePool::~MotionNodePool() {
  assert(in_use_ == 0 && "a tree outlived its node pool");
  for (Chunk* c : spare_) delete c;
}

MotionNodePool::Chunk* MotionNodePool::take() {
  {
    const std::lock_guard lock(mutex_);
    ++in_use_;
    if (!spare_.empty()) {
      Chunk* c = spare_.back();
      spare_.pop_back();
      return c;
    }
  }
  return new Chunk;  // outside the lock: only the first time the trees together hold this many
}

void MotionNodePool::give_back(std::span<Chunk* const> chunks) {
  if (chunks.empty()) return;
  const std::lock_guard lock(mutex_);
  assert(in_use_ >= chunks.size());
  in_use_ -= chunks.size();
  spare_.insert(spare_.end(), chunks.begin(), chunks.end());
  // Also trims what earlier, larger crowds left: the spare follows the chunks in use down.
  const size_t keep = std::max(kMinSpare, in_use_ / 16);
  while (spare_.size() > keep) {
    delete spare_.back();
    spare_.pop_back();
  }
}

size_t MotionNodePool::bytes_spare() const {
  const std::lock_guard lock(mutex_);
  return spare_.size() * sizeof(Chunk);
}

size_t MotionNodePool::bytes_in_use() const {
  const std::lock_guard lock(mutex_);
  return in_use_ * sizeof(Chunk);
}

}  // namespace foresight

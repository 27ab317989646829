#pragma once
// The avatar history the packet fuzzer decodes snapshots against, and the seeds are coded
// against: one earlier snapshot (number 1) holding avatars 1-8, so references to it resolve.
#include "protocol/avatar_delta.hpp"

namespace foresight::fuzz {

inline protocol::AvatarHistory fuzz_history() {
  protocol::AvatarHistory h;
  protocol::AvatarHistory::Slot& s = h.start(1, 1);
  for (uint32_t id = 1; id <= 8; ++id) s.avatars.emplace_back(id, 1000, -1000, 3, 2, 100, 5, 0, 0);
  h.acknowledge(1);
  return h;
}

}  // namespace foresight::fuzz

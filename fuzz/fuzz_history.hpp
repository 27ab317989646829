#pragma once
// The avatar history the packet fuzzer decodes snapshots against, and the seeds are coded
// against: one earlier snapshot (number 1) holding avatars 1-8, so references to it resolve.
#include "protocol/avatar_delta.hpp"
#include "protocol/sent_views.hpp"

#include <vector>

namespace foresight::fuzz {

inline std::vector<wire::AvatarState> fuzz_history_avatars() {
  std::vector<wire::AvatarState> avatars;
  for (uint32_t id = 1; id <= 8; ++id) avatars.emplace_back(id, 1000, -1000, 3, 2, 100, 5, 0, 0);
  return avatars;
}

/// The receiver's side (what the fuzzer decodes against).
inline protocol::AvatarHistory fuzz_history() {
  protocol::AvatarHistory h;
  protocol::AvatarHistory::Slot& s = h.start(1, 1);
  s.avatars = fuzz_history_avatars();
  s.usable = true;
  return h;
}

/// The sender's side (what the seeds are coded against).
inline void fuzz_sent(protocol::WholeViewSender& sender) {
  sender.remember(1, 1, fuzz_history_avatars());
  sender.acknowledge(1);
}

}  // namespace foresight::fuzz

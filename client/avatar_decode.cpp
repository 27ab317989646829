#include "avatar_decode.hpp"

#include "protocol/avatar_state.hpp"
#include "protocol/protocol.hpp"

namespace foresight::client {

bool avatar_entry_from_wire(const MotionLibrary& library, const wire::AvatarState& state,
                            AvatarEntry& out) {
  if (!protocol::avatar_playback(library, state, out.state)) return false;
  out.id = state.id();
  out.flags = state.flags();
  return true;
}

int avatar_entries_from_wire(const MotionLibrary& library, std::span<const wire::AvatarState> avatars,
                             std::vector<AvatarEntry>& out) {
  out.clear();
  int rejected = 0;
  for (const auto& a : avatars) {
    if (a.flags() & protocol::kAvatarTerrain) continue;  // drawn from its TerrainBody (terrain_poses.hpp)
    AvatarEntry e;
    if (avatar_entry_from_wire(library, a, e)) out.push_back(e);
    else ++rejected;
  }
  return rejected;
}

}  // namespace foresight::client

#pragma once
// The avatars in play, one table per kind (handle_table.hpp), and the roster that lists them all
// in id order. A stage loops over the one table it works on; the snapshot walks the roster, which
// is already in the order the packed avatars want, so nothing is sorted per snapshot.
//
//   GraphAvatar    walks the motion graph with a feasible motion tree: a player's avatar, or an
//                  NPC fighter's body
//   TerrainWalker  walks uneven ground with the footstep planners (Locomotion::kTerrain)
//   Fighter        an NPC fighter's brain and strike motion, driving one GraphAvatar
#include "fighters/fighter_npc.hpp"
#include "handle_table.hpp"
#include "lookahead/lookahead_avatar.hpp"
#include "terrain/terrain_avatar.hpp"
#include "world/control_input.hpp"

#include <algorithm>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace foresight::server {

enum class AvatarKind : uint8_t { kGraph, kTerrain };

struct GraphAvatar {
  uint32_t id = 0;
  std::unique_ptr<LookaheadAvatar> avatar;
  ControlInput input;          ///< The command held: a player's keys, or a fighter brain's direction.
  bool input_changed = true;   ///< Not yet given to the tree (the look-ahead stage does).
  Handle fighter;              ///< Its fighter, for an NPC's body; stale (never valid) for a player.
  bool npc = false;
  bool striking = false;       ///< A fighter's strike is playing (set when fighters animate).
};

struct TerrainWalker {
  uint32_t id = 0;
  std::unique_ptr<terrain::TerrainAvatar> avatar;
  ControlInput input;
};

struct Fighter {
  uint32_t id = 0;
  Handle body;  ///< Its GraphAvatar.
  std::unique_ptr<FighterNpc> npc;
};

struct RosterEntry {
  uint32_t id = 0;
  AvatarKind kind = AvatarKind::kGraph;
  Handle avatar;  ///< In the table of its kind.
};

/// Every avatar in play, in id order. Ids only grow, so a new avatar goes at the end; one that
/// leaves is found by binary search.
class Roster {
 public:
  void reserve(size_t n) { entries_.reserve(n); }
  void add(const RosterEntry& e) { entries_.push_back(e); }
  void remove(uint32_t id) {
    if (const RosterEntry* e = find(id)) entries_.erase(entries_.begin() + (e - entries_.data()));
  }
  const RosterEntry* find(uint32_t id) const {
    const auto it = std::lower_bound(entries_.begin(), entries_.end(), id,
                                     [](const RosterEntry& e, uint32_t v) { return e.id < v; });
    return it != entries_.end() && it->id == id ? &*it : nullptr;
  }
  /// Index of `id` in entries() (the avatar's place in a snapshot), or -1.
  int index_of(uint32_t id) const {
    const RosterEntry* e = find(id);
    return e ? static_cast<int>(e - entries_.data()) : -1;
  }
  std::span<const RosterEntry> entries() const { return entries_; }

 private:
  std::vector<RosterEntry> entries_;
};

}  // namespace foresight::server

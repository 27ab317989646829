#pragma once
// Snapshot avatars, delta-coded and bit-packed (issue 8; docs/PROTOCOL.md "Packed avatars").
//
// Each avatar of a snapshot part is coded against its state in an earlier snapshot the client
// has acknowledged (its *reference*), usually the newest one holding that avatar: an avatar still
// playing the segment it played there, at the frame that segment has reached since, costs its id
// gap and 5 bits (plus the reference's index when a part has several); a new segment costs its
// changed fields as differences (about 60 bits); an avatar the client has no acknowledged state
// of is sent whole (about 100 bits). A plain AvatarState is 192 bits.
//
// The client keeps the snapshots it decoded whole (AvatarHistory, every part); the server keeps
// what it sent each client and which of those snapshots the client acknowledged (SentViews over
// one SnapshotArchive, sent_views.hpp). The server only refers to snapshots the client
// acknowledged, and the client acknowledges only snapshots it holds whole, so every reference can
// be resolved; one that cannot (a client that lost its history) is an error, and the client then
// keeps acknowledging its last whole snapshot until the server's references age out of the
// history and it sends whole states again. Both histories hold the client's last 64 snapshots
// (3.2 s at 20 Hz; the server's archive as many of those it gathered as span them, sent_views.hpp), so delta coding
// survives a round trip of 2 s and more.
//
// Part format (BitWriter codes, bit_stream.hpp):
//   S: width of segments (5 bits), T: width of transitions + 1 (6 bits)
//   refs: 3 bits, then per reference: snapshots back (6 bits, 1..63), server ticks since it (gamma of n + 1)
//   per avatar, in increasing id order (the count is the Snapshot's avatar_count):
//     id - previous id (gamma; the previous id of the first is -1)
//     with refs: 1 bit "has a reference", and its index (ceil(log2(refs)) bits) if refs > 1
//     with a reference R:
//       1 bit same play-through (segment, transition, start and heading as in R)
//         yes: 1 bit frame == R.frame + ticks since R, else the difference to it (signed gamma)
//         no:  segment (S bits), transition + 1 (T bits), start x, z and heading minus R's (signed
//              wide), frame + 1 (gamma)
//       1 bit flags as in R, else 8 bits
//     without: segment (S), transition + 1 (T), start x, z (signed wide), heading (16 bits),
//              frame + 1 (gamma), flags (8 bits)
//     1 bit reserved == 0, else 16 bits
#include "protocol/bit_stream.hpp"
#include "foresight_generated.h"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace foresight::protocol {

/// The receiver's side: the avatar lists of the last kSlots snapshots it decoded, by snapshot
/// number (Snapshot::tick), what the packed avatars' references resolve in.
class AvatarHistory {
 public:
  static constexpr uint32_t kSlots = 64;
  struct Slot {
    uint32_t snapshot = 0;
    uint32_t server_tick = 0;
    bool valid = false;
    bool usable = false;  ///< Every part of it was decoded.
    std::vector<wire::AvatarState> avatars;  ///< Sorted by id.
    const wire::AvatarState* find(uint32_t id) const;
  };

  /// The slot of `snapshot`, emptied (and not usable); it replaces the snapshot kSlots earlier.
  Slot& start(uint32_t snapshot, uint32_t server_tick);
  Slot* find(uint32_t snapshot);
  const Slot* find(uint32_t snapshot) const;
  void clear();
  /// Room for this many avatars in every slot (then start() and assigning up to that allocate nothing).
  void reserve(size_t avatars);

 private:
  std::array<Slot, kSlots> slots_;
};

/// References reach back at most this many snapshots (the 6-bit field), inside the histories.
inline constexpr uint32_t kMaxReferenceBack = AvatarHistory::kSlots - 1;

/// What the sender codes one view avatar against: the state the receiver holds of it in an
/// earlier, acknowledged snapshot (SentViews::references fills them).
struct AvatarReference {
  bool found = false;
  uint32_t snapshot = 0;
  uint32_t server_tick = 0;
  wire::AvatarState state;  ///< As the receiver holds it (its flags included).
};

/// Writes one client's view of a snapshot as packed parts. plan() once per snapshot, then per part
/// begin_part(), add() for a run of avatars in increasing id order and finish() (or write_part()).
class AvatarDeltaEncoder {
 public:
  /// Worst case bytes of one add() (so a part can be closed before it overflows).
  static constexpr size_t kMaxAvatarBytes = 40;

  /// `view`: sorted by id; `references`: one per view avatar, or none at all (everything whole);
  /// both alive until the last add().
  void plan(std::span<const wire::AvatarState> view, uint32_t snapshot, uint32_t server_tick,
            std::span<const AvatarReference> references);
  void begin_part(BitWriter& out);
  /// Codes view[index]. The part is complete after out.finish().
  void add(size_t index, BitWriter& out);
  /// A whole part of view[begin, end) into `out`.
  void write_part(size_t begin, size_t end, std::vector<uint8_t>& out);

  /// Of the planned view: avatars with a reference, and those coded whole.
  size_t referenced() const { return referenced_; }

 private:
  struct Ref {
    uint32_t back = 0;
    uint32_t ticks = 0;
  };
  std::span<const wire::AvatarState> view_;
  std::array<Ref, 7> refs_{};
  int num_refs_ = 0;
  int index_bits_ = 0;
  int segment_bits_ = 0, transition_bits_ = 0;  ///< Widths of the view's largest segment, transition + 1.
  std::vector<int8_t> ref_of_;  ///< Per view avatar: index into refs_, -1 whole.
  std::vector<const wire::AvatarState*> reference_;
  int64_t previous_id_ = -1;
  size_t referenced_ = 0;
};

enum class AvatarDecodeStatus : uint8_t {
  kOk,
  kMalformed,        ///< Cut off, ids not increasing, a reference index out of range, trailing bytes.
  kMissingBaseline,  ///< A reference to a snapshot (or an avatar in it) this side does not hold.
};

/// Appends the `count` avatars of one packed part to `out`. Resolves references in `history`'s
/// usable slots. On an error `out` is left as it was.
AvatarDecodeStatus decode_avatars(std::span<const uint8_t> packed, uint32_t count, uint32_t snapshot,
                                  const AvatarHistory& history, std::vector<wire::AvatarState>& out);

/// decode_avatars() of a Snapshot part (avatar_count, avatar_bits, tick).
AvatarDecodeStatus snapshot_avatars(const wire::Snapshot& m, const AvatarHistory& history,
                                    std::vector<wire::AvatarState>& out);

/// `avatars` (sorted by id) packed whole into `out`, as for a client that acknowledged nothing
/// (tests and tools build snapshots with it).
void pack_avatars(std::span<const wire::AvatarState> avatars, std::vector<uint8_t>& out);

}  // namespace foresight::protocol

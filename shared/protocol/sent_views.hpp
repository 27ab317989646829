#pragma once
// The sender's memory of the snapshots it sent, for the packed avatars' references
// (avatar_delta.hpp), sized in time: a receiver's last 64 snapshots, 3.2 s at 20 Hz, so delta coding survives a
// round trip of 2 s and more.
//
// Every receiver's view of a snapshot is a subset of the same avatars, differing only in the
// per-receiver flags kAvatarYours and kAvatarFar. So the avatars of each snapshot are kept once
// (SnapshotArchive, shared by all receivers) and, per receiver, only which of them went into its
// view and which as far ones (SentViews: 2 bits an archived avatar, for each snapshot not yet
// acknowledged), and per avatar the newest acknowledged snapshot that held it, with its far flag.
// An acknowledged snapshot's bits are merged into that list and their storage goes back to the
// receiver's spare bit sets, so a receiver holds bits for the snapshots in flight (a few on a good
// link; up to 64 when acknowledgements stop), not for all 64: 250 bytes each with 1000 avatars.
// Copying each view whole per receiver would cost 64 x 24 bytes per avatar in view: 300 KB per
// receiver seeing 200 avatars.
#include "protocol/avatar_delta.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace foresight::protocol {

/// The avatars of the last snapshots gathered, by their number in the archive, as the world had
/// them (without per-receiver flags). A receiver numbers the snapshots it gets one by one
/// (Snapshot::tick) and need not get every one gathered (the server serves each client on its own
/// ticks), so the archive keeps as many as a receiver's references reach back over: 64 of a
/// receiver's snapshots at 20 Hz span 96 gathered on 30 Hz ticks (slots_for).
class SnapshotArchive {
 public:
  /// Slots that hold a receiver's last AvatarHistory::kSlots snapshots when the sender gathers one
  /// every tick and serves each receiver `snapshot_hz` of its `tick_hz` ticks a second.
  static uint32_t slots_for(int tick_hz, int snapshot_hz);
  explicit SnapshotArchive(uint32_t slots = AvatarHistory::kSlots) : slots_(slots) {}
  struct Slot {
    uint32_t snapshot = 0;
    uint32_t server_tick = 0;
    bool valid = false;
    std::vector<wire::AvatarState> avatars;  ///< Sorted by id.
  };

  /// The slot of `snapshot`, emptied; it replaces the snapshot as many slots earlier.
  Slot& start(uint32_t snapshot, uint32_t server_tick);
  const Slot* find(uint32_t snapshot) const;
  /// Bytes held (capacity), for the server's memory report.
  size_t bytes() const;

 private:
  std::vector<Slot> slots_;
};

/// One receiver's views of the archived snapshots: which avatars, which of them far, which
/// snapshots it acknowledged. Allocates nothing once it has as many bit sets, grown to the
/// archive's size, as snapshots are in flight at once.
class SentViews {
 public:
  /// The receiver's own avatar: the one sent with kAvatarYours.
  void set_owner(uint32_t avatar_id) { owner_ = avatar_id; }
  /// Records the view the receiver got as its `snapshot` (its own numbering): the avatars of
  /// `archived` (the archive's slot it was cut from) at `indices`, `far[k]` non-zero for those
  /// sent with kAvatarFar (empty: none).
  void record(uint32_t snapshot, const SnapshotArchive::Slot& archived, std::span<const uint32_t> indices,
              std::span<const uint8_t> far);
  /// The receiver holds `snapshot` whole (archived in `archive`): later views may be coded
  /// against it. Notes, per avatar, the newest acknowledged snapshot holding it.
  void acknowledge(const SnapshotArchive& archive, uint32_t snapshot);
  /// Notes that the receiver acknowledged `snapshot`, merged by acknowledge_queued(): the server
  /// reads acknowledgements on the tick thread as inputs arrive and merges them (most of an
  /// acknowledgement's cost) on the worker that serves the client next. A repeat of the newest
  /// queued one is dropped; with the queue full, the oldest is merged now.
  void queue_acknowledgement(const SnapshotArchive& archive, uint32_t snapshot);
  /// acknowledge() of each queued snapshot, in the order they came.
  void acknowledge_queued(const SnapshotArchive& archive);
  /// For each avatar of `view` (sorted by id), the newest acknowledged state the receiver holds of
  /// it, at most kMaxReferenceBack snapshots before `snapshot`, as it was sent (flags included).
  void references(const SnapshotArchive& archive, std::span<const wire::AvatarState> view, uint32_t snapshot,
                  std::vector<AvatarReference>& out) const;
  size_t bytes() const;

 private:
  static constexpr uint8_t kNoBits = 0xFF;
  /// 12 bytes: a receiver has 64, most of them acknowledged long ago and needing only their
  /// archive number, so the bit sets live apart, in bit_sets_, while the snapshot is in flight.
  struct Slot {
    uint32_t snapshot = 0;     ///< The receiver's number.
    uint32_t archived_as = 0;  ///< The archive's number of the snapshot it was cut from.
    bool valid = false;
    bool acknowledged = false;
    /// Its view in bit_sets_ (archive index i: bit 2i in view, bit 2i + 1 far) until it is
    /// acknowledged (merged into newest_) or let go; kNoBits after.
    uint8_t bit_set = kNoBits;
  };
  std::array<Slot, AvatarHistory::kSlots> slots_;  ///< By the receiver's number.
  /// A free bit set's index (one given back, with its storage, if any).
  uint8_t take_bit_set();
  /// Gives `s`'s bit set back (its storage kept for reuse, or freed when enough are spare).
  void release_bits(Slot& s);
  static constexpr uint32_t kLateAckSnapshots = 8;  ///< 0.4 s at 20 Hz.
  static constexpr size_t kMaxSpareBitSets = 8;
  std::vector<std::vector<uint64_t>> bit_sets_;  ///< At most one per slot.
  std::vector<uint8_t> free_bit_sets_;           ///< Indices into bit_sets_ not in use.
  uint32_t newest_acknowledged_ = 0;
  bool any_acknowledged_ = false;
  std::array<uint32_t, 4> queued_{};  ///< Acknowledgements not merged yet, oldest first.
  uint32_t num_queued_ = 0;
  uint32_t owner_ = 0;
  /// By id: the newest acknowledged snapshot that held the avatar, where in that snapshot's
  /// archive, and whether it went there as a far one (entries out of reach are dropped as
  /// acknowledgements come). A reference costs one lookup per avatar: no search through 63
  /// snapshots for the far ones that come every few, no search of the archived snapshot.
  struct Newest {
    uint32_t id = 0;
    uint32_t snapshot = 0;    ///< The receiver's number.
    uint32_t index : 31 = 0;  ///< In the archive's slot `snapshot` was cut from.
    uint32_t far : 1 = 0;
  };
  std::vector<Newest> newest_;
};

/// A sender with one receiver whose views are whole snapshots, flags included (tests, tools, the
/// fuzzer's seeds): each view archived as it is.
class WholeViewSender {
 public:
  /// The view sent as `snapshot` (sorted by id).
  void remember(uint32_t snapshot, uint32_t server_tick, std::span<const wire::AvatarState> view);
  void acknowledge(uint32_t snapshot) { views_.acknowledge(archive_, snapshot); }
  /// encoder.plan() of `view` against what was acknowledged.
  void plan(AvatarDeltaEncoder& encoder, std::span<const wire::AvatarState> view, uint32_t snapshot,
            uint32_t server_tick);

 private:
  SnapshotArchive archive_;
  SentViews views_;
  std::vector<uint32_t> indices_;
  std::vector<AvatarReference> references_;
};

}  // namespace foresight::protocol

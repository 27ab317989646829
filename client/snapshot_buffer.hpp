#pragma once
// The client's interpolation buffer (docs/CLIENT.md): received snapshots, ordered by the server's
// time, played back `delay` behind the newest so there is (nearly) always a snapshot on each side
// of the time shown. Between two snapshots an avatar's clip frames advance smoothly; across a
// segment change the earlier segment plays forward into the later one (entered by its transition),
// exactly as the server played it. When snapshots are late the newest state is extrapolated
// forward, at most `max_extrapolation`, then held.
//
// Fixed capacity: once warm (every slot has held the largest snapshot seen), push() and sample()
// allocate nothing.
#include "library/playback.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace foresight::client {

/// One avatar as a snapshot describes it (already checked against the library).
struct AvatarEntry {
  uint32_t id = 0;
  PlaybackState state;
  uint8_t flags = 0;  ///< protocol::AvatarFlags.
};

/// What to draw for one avatar: a playback state (frame may be fractional through frame_alpha).
struct ShownAvatar {
  uint32_t id = 0;
  PlaybackState state;
  float frame_alpha = 0.0f;  ///< Fraction of the way from state.frame to state.frame + 1.
  uint8_t flags = 0;
  bool extrapolated = false;  ///< Shown past the newest snapshot holding it.
};

struct SnapshotBufferConfig {
  double delay_s = 0.100;              ///< How far behind the newest snapshot playback runs.
  double max_extrapolation_s = 0.250;  ///< Past the newest snapshot, advance at most this far.
  int capacity = 32;                   ///< Snapshots kept (20 Hz: 1.6 s).
  /// An avatar flagged kAvatarFar (beyond the server's interest radius: sent every few snapshots)
  /// stays shown this long after its last snapshot, interpolated to its next one.
  double far_hold_s = 0.6;
};

class SnapshotBuffer {
 public:
  explicit SnapshotBuffer(const SnapshotBufferConfig& config = {});

  /// Adds a snapshot taken at server time `server_time_s` that arrived at local time `local_s`.
  /// A snapshot with the time of one already held replaces it (later parts of the same tick);
  /// one older than everything held when the buffer is full is dropped.
  void push(double server_time_s, double local_s, std::span<const AvatarEntry> avatars);
  /// Forgets everything (a new session).
  void clear();

  /// The server time shown at local time `local_s`: local time mapped to server time, minus the delay.
  double render_time(double local_s) const { return local_s + clock_offset_s_ - config_.delay_s; }
  /// Every avatar to draw at server time `t` (see render_time), sorted by id.
  void sample(const MotionLibrary& library, double t, std::vector<ShownAvatar>& out) const;

  size_t size() const { return count_; }
  double newest_time() const;
  const SnapshotBufferConfig& config() const { return config_; }

 private:
  struct Snapshot {
    double time_s = 0;
    std::vector<AvatarEntry> avatars;  ///< Sorted by id.
    const AvatarEntry* find(uint32_t id) const;
  };
  const Snapshot& at(size_t i) const { return slots_[order_[i]]; }
  ShownAvatar show(const MotionLibrary& library, size_t j, const AvatarEntry& a, double t) const;

  SnapshotBufferConfig config_;
  std::vector<Snapshot> slots_;  ///< Storage, reused.
  std::vector<size_t> order_;    ///< Slot indices by ascending time; first count_ are live.
  size_t count_ = 0;
  double clock_offset_s_ = 0;    ///< Server time minus local time (smoothed).
  bool has_offset_ = false;
};

/// Advances `state` by `frames` (fractional) clip frames through its segment; at the segment's
/// end it stops (the successor is unknown). Sets frame and alpha.
void advance_frames(const MotionLibrary& library, PlaybackState& state, float& alpha, double frames);

}  // namespace foresight::client

#include "snapshot_buffer.hpp"

#include "protocol/protocol.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace foresight::client {

namespace {

// How fast the server-minus-local clock offset follows new samples. A sample above the estimate
// came through faster than usual (less queueing): follow it quickly. One below it was delayed:
// follow slowly, so one late packet does not pull playback back.
constexpr double kOffsetRiseRate = 0.5;
constexpr double kOffsetFallRate = 0.02;
constexpr double kOffsetSnapS = 1.0;  ///< Further off than this: a new session or a stall; jump.

int segment_frames(const MotionLibrary& library, int segment) {
  return library.graph.segments[static_cast<size_t>(segment)].num_frames();
}

float segment_fps(const MotionLibrary& library, int segment) {
  const int clip = library.graph.segments[static_cast<size_t>(segment)].clip;
  return library.clips[static_cast<size_t>(clip)].fps;
}

// One play-through of a segment, `b` later, `elapsed_frames` of clip time after `a`. Steering mode
// (docs/LOOKAHEAD.md) turns a playing segment about the root, so its start changes while it
// plays; then b's frame is a's plus the time between them, where a new play-through of the same
// segment would have played a's rest first.
bool same_playthrough(const MotionLibrary& library, const PlaybackState& a, const PlaybackState& b,
                      double elapsed_frames) {
  if (a.segment != b.segment || a.incoming_transition != b.incoming_transition || b.frame < a.frame) return false;
  if (a.segment_start.pos_m == b.segment_start.pos_m && a.segment_start.heading_rad == b.segment_start.heading_rad)
    return true;
  const double same = b.frame - a.frame;
  const double again = segment_frames(library, a.segment) - a.frame + b.frame;
  return std::abs(same - elapsed_frames) < std::abs(again - elapsed_frames);
}

// The state `alpha` of the way from `a` to `b` (b later). Within one play-through of a segment
// the frame moves linearly (and a steered start turns with it); otherwise `a` plays to its end,
// then `b`'s segment from its start (skipped segments in between, if packets were lost, are not
// reconstructed).
void interpolate(const MotionLibrary& library, const PlaybackState& a, const PlaybackState& b,
                 double alpha, double elapsed_frames, ShownAvatar& out) {
  if (same_playthrough(library, a, b, elapsed_frames)) {
    out.state = a;
    if (a.segment_start.heading_rad != b.segment_start.heading_rad || a.segment_start.pos_m != b.segment_start.pos_m) {
      const float w = static_cast<float>(alpha);
      out.state.segment_start.pos_m = glm::mix(a.segment_start.pos_m, b.segment_start.pos_m, w);
      out.state.segment_start.heading_rad =
          a.segment_start.heading_rad + w * wrap_angle(b.segment_start.heading_rad - a.segment_start.heading_rad);
    }
    advance_frames(library, out.state, out.frame_alpha, alpha * (b.frame - a.frame));
    return;
  }
  const double remaining = std::max(0, segment_frames(library, a.segment) - a.frame);
  const double p = alpha * (remaining + b.frame);
  if (p < remaining) {
    out.state = a;
    advance_frames(library, out.state, out.frame_alpha, p);
  } else {
    out.state = b;
    out.state.frame = 0;
    advance_frames(library, out.state, out.frame_alpha, p - remaining);
  }
}

}  // namespace

void advance_frames(const MotionLibrary& library, PlaybackState& state, float& alpha, double frames) {
  const int n = segment_frames(library, state.segment);
  const double f = std::clamp(state.frame + std::max(0.0, frames), 0.0, static_cast<double>(n));
  state.frame = std::min(static_cast<int>(std::floor(f)), n);
  alpha = state.frame >= n ? 0.0f : static_cast<float>(f - state.frame);
}

const AvatarEntry* SnapshotBuffer::Snapshot::find(uint32_t id) const {
  const auto it = std::lower_bound(avatars.begin(), avatars.end(), id,
                                   [](const AvatarEntry& e, uint32_t v) { return e.id < v; });
  return it != avatars.end() && it->id == id ? &*it : nullptr;
}

SnapshotBuffer::SnapshotBuffer(const SnapshotBufferConfig& config) : config_(config) {
  config_.capacity = std::max(config_.capacity, 2);
  slots_.resize(static_cast<size_t>(config_.capacity));
  for (auto& s : slots_) s.avatars.reserve(256);
  order_.resize(slots_.size());
  std::iota(order_.begin(), order_.end(), size_t{0});
}

void SnapshotBuffer::clear() {
  count_ = 0;
  has_offset_ = false;
  std::iota(order_.begin(), order_.end(), size_t{0});
}

double SnapshotBuffer::newest_time() const { return count_ ? at(count_ - 1).time_s : 0.0; }

void SnapshotBuffer::push(double server_time_s, double local_s, std::span<const AvatarEntry> avatars) {
  const double sample = server_time_s - local_s;
  if (!has_offset_ || std::abs(sample - clock_offset_s_) > kOffsetSnapS) {
    clock_offset_s_ = sample;
    has_offset_ = true;
  } else {
    clock_offset_s_ += (sample > clock_offset_s_ ? kOffsetRiseRate : kOffsetFallRate) *
                       (sample - clock_offset_s_);
  }

  // Where it goes in time order.
  const auto live_end = order_.begin() + static_cast<std::ptrdiff_t>(count_);
  auto pos = std::lower_bound(order_.begin(), live_end, server_time_s,
                              [this](size_t slot, double t) { return slots_[slot].time_s < t; });
  size_t slot;
  if (pos != live_end && slots_[*pos].time_s == server_time_s) {
    slot = *pos;  // The same tick again (another part): replace.
  } else if (count_ < order_.size()) {
    slot = order_[count_];  // A free slot: move it into place.
    std::rotate(pos, live_end, live_end + 1);
    ++count_;
  } else {
    if (pos == order_.begin()) return;  // Older than everything kept: too late to matter.
    slot = order_[0];                    // Reuse the oldest: shift the older ones down.
    std::rotate(order_.begin(), order_.begin() + 1, pos);
    *(pos - 1) = slot;
  }
  Snapshot& s = slots_[slot];
  s.time_s = server_time_s;
  s.avatars.assign(avatars.begin(), avatars.end());
  std::sort(s.avatars.begin(), s.avatars.end(),
            [](const AvatarEntry& a, const AvatarEntry& b) { return a.id < b.id; });
}

// Avatar `a` as held by snapshot j (at or before t): interpolated towards the next snapshot holding
// it (a lost part may have left it out of the very next), else played on at the clip's rate,
// capped (late, or gone next).
ShownAvatar SnapshotBuffer::show(const MotionLibrary& library, size_t j, const AvatarEntry& a, double t) const {
  ShownAvatar shown;
  shown.id = a.id;
  shown.flags = a.flags;
  const double t0 = at(j).time_s;
  const AvatarEntry* b = nullptr;
  double t1 = 0;
  for (size_t k = j + 1; k < count_ && !b; ++k) {
    b = at(k).find(a.id);
    t1 = at(k).time_s;
  }
  if (t <= t0) {
    shown.state = a.state;
  } else if (b) {
    interpolate(library, a.state, b->state, (t - t0) / (t1 - t0), (t1 - t0) * segment_fps(library, a.state.segment),
                shown);
    shown.flags = b->flags;
  } else {
    shown.state = a.state;
    advance_frames(library, shown.state, shown.frame_alpha,
                   std::min(t - t0, config_.max_extrapolation_s) * segment_fps(library, a.state.segment));
    shown.extrapolated = true;
  }
  return shown;
}

void SnapshotBuffer::sample(const MotionLibrary& library, double t, std::vector<ShownAvatar>& out) const {
  out.clear();
  if (count_ == 0) return;
  // The newest snapshot at or before t decides who is shown (before the oldest: the oldest, held).
  size_t i0 = 0;
  while (i0 + 1 < count_ && at(i0 + 1).time_s <= t) ++i0;
  const Snapshot& s0 = at(i0);
  for (const AvatarEntry& a : s0.avatars) out.push_back(show(library, i0, a, t));
  // Far avatars come every few snapshots: those missing from s0 are shown from their own newest
  // snapshot at or before t (within far_hold_s).
  const size_t from_s0 = out.size();
  for (size_t j = i0; j-- > 0 && at(j).time_s >= t - config_.far_hold_s;) {
    for (const AvatarEntry& a : at(j).avatars) {
      if (!(a.flags & protocol::kAvatarFar) || s0.find(a.id) != nullptr) continue;
      if (std::any_of(out.begin() + static_cast<std::ptrdiff_t>(from_s0), out.end(),
                      [&](const ShownAvatar& x) { return x.id == a.id; }))
        continue;  // a newer snapshot held it already
      out.push_back(show(library, j, a, t));
    }
  }
  if (out.size() > from_s0)
    std::sort(out.begin(), out.end(), [](const ShownAvatar& x, const ShownAvatar& y) { return x.id < y.id; });
}

}  // namespace foresight::client

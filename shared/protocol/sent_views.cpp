#include "protocol/sent_views.hpp"

#include "protocol/protocol.hpp"

#include <algorithm>
#include <bit>

namespace foresight::protocol {

uint32_t SnapshotArchive::slots_for(int tick_hz, int snapshot_hz) {
  const auto ticks = static_cast<uint32_t>(std::max(tick_hz, 1));
  const auto served = static_cast<uint32_t>(std::clamp(snapshot_hz, 1, static_cast<int>(ticks)));
  return (AvatarHistory::kSlots * ticks + served - 1) / served;
}

SnapshotArchive::Slot& SnapshotArchive::start(uint32_t snapshot, uint32_t server_tick) {
  Slot& s = slots_[snapshot % slots_.size()];
  s.snapshot = snapshot;
  s.server_tick = server_tick;
  s.valid = true;
  s.avatars.clear();
  return s;
}

const SnapshotArchive::Slot* SnapshotArchive::find(uint32_t snapshot) const {
  const Slot& s = slots_[snapshot % slots_.size()];
  return s.valid && s.snapshot == snapshot ? &s : nullptr;
}

size_t SnapshotArchive::bytes() const {
  size_t n = sizeof(*this) + slots_.capacity() * sizeof(Slot);
  for (const Slot& s : slots_) n += s.avatars.capacity() * sizeof(wire::AvatarState);
  return n;
}

void SentViews::record(uint32_t snapshot, const SnapshotArchive::Slot& archive_slot, std::span<const uint32_t> indices,
                       std::span<const uint8_t> far) {
  const size_t archived = archive_slot.avatars.size();
  Slot& s = slots_[snapshot % slots_.size()];
  s.snapshot = snapshot;
  s.archived_as = archive_slot.snapshot;
  s.valid = true;
  s.acknowledged = false;
  if (s.bit_set == kNoBits) s.bit_set = take_bit_set();  // else the set of the snapshot it replaces
  std::vector<uint64_t>& bits = bit_sets_[s.bit_set];
  bits.assign((2 * archived + 63) / 64, 0);
  for (size_t k = 0; k < indices.size(); ++k) {
    const size_t i = indices[k];
    if (i >= archived) continue;
    bits[2 * i / 64] |= uint64_t{1} << (2 * i % 64);
    if (k < far.size() && far[k] != 0) bits[(2 * i + 1) / 64] |= uint64_t{1} << ((2 * i + 1) % 64);
  }
}

uint8_t SentViews::take_bit_set() {
  if (free_bit_sets_.empty()) {
    bit_sets_.emplace_back();
    return static_cast<uint8_t>(bit_sets_.size() - 1);  // at most one per slot: 64
  }
  const uint8_t i = free_bit_sets_.back();
  free_bit_sets_.pop_back();
  return i;
}

void SentViews::acknowledge(const SnapshotArchive& archive, uint32_t snapshot) {
  Slot& s = slots_[snapshot % slots_.size()];
  if (!s.valid || s.snapshot != snapshot || s.acknowledged) return;
  const SnapshotArchive::Slot* a = archive.find(s.archived_as);
  if (a == nullptr) return;
  s.acknowledged = true;
  // Merge the snapshot's view (its archived avatars whose bit is set, in id order) into newest_
  // (by id), keeping per id the newer snapshot (acknowledgements may come out of order) and
  // dropping what is out of reach.
  const auto newer = [](uint32_t x, uint32_t y) { return static_cast<int32_t>(x - y) > 0; };
  const auto in_reach = [&](const Newest& n) {
    return snapshot - n.snapshot <= kMaxReferenceBack || newer(n.snapshot, snapshot);
  };
  thread_local std::vector<Newest> merged;  // scratch, the thread's (not one per receiver)
  merged.clear();
  size_t k = 0;
  // Only the avatars in the view: the set "in view" bits (even bits), word by word. A view holds
  // a few dozen of the 1000 archived avatars; testing each archived one cost a tenth of the
  // server's time at 1000 players.
  constexpr uint64_t kInViewBits = 0x5555555555555555ull;
  const std::vector<uint64_t>& bits = bit_sets_[s.bit_set];
  for (size_t w = 0; w < bits.size(); ++w) {
    for (uint64_t in_view = bits[w] & kInViewBits; in_view != 0; in_view &= in_view - 1) {
      const int bit = std::countr_zero(in_view);
      const size_t i = (w * 64 + static_cast<size_t>(bit)) / 2;
      if (i >= a->avatars.size()) break;
      const uint32_t id = a->avatars[i].id();
      for (; k < newest_.size() && newest_[k].id < id; ++k)
        if (in_reach(newest_[k])) merged.push_back(newest_[k]);
      Newest n{id, snapshot, static_cast<uint32_t>(i), static_cast<uint32_t>(bits[w] >> (bit + 1) & 1)};
      if (k < newest_.size() && newest_[k].id == id) {
        if (newer(newest_[k].snapshot, snapshot)) n = newest_[k];
        ++k;
      }
      merged.push_back(n);
    }
  }
  for (; k < newest_.size(); ++k)
    if (in_reach(newest_[k])) merged.push_back(newest_[k]);
  // newest_ keeps its own storage (assign, not swap): the scratch's capacity stays with the thread.
  newest_.assign(merged.begin(), merged.end());
  release_bits(s);
  // A client acknowledges only the newest snapshot it holds, so one that came right behind
  // another is never acknowledged: its bits would wait 64 snapshots for the slot to be reused.
  // Those well behind this one (kLateAckSnapshots: later than any acknowledgement that still comes
  // out of order) are let go now.
  if (!any_acknowledged_ || newer(snapshot, newest_acknowledged_)) {
    const uint32_t before = snapshot - kLateAckSnapshots;
    uint32_t n = any_acknowledged_ ? newest_acknowledged_ - kLateAckSnapshots : before - kMaxReferenceBack;
    if (newer(before - static_cast<uint32_t>(slots_.size()), n)) n = before - static_cast<uint32_t>(slots_.size());
    for (; newer(before, n); ++n) {
      Slot& old = slots_[n % slots_.size()];
      if (old.valid && old.snapshot == n && !old.acknowledged) old.valid = false, release_bits(old);
    }
    newest_acknowledged_ = snapshot;
    any_acknowledged_ = true;
  }
}

void SentViews::release_bits(Slot& s) {
  if (s.bit_set == kNoBits) return;
  // At most kMaxSpareBitSets keep their storage: a client whose acknowledgements stopped for a
  // while (up to 64 bit sets in flight) gives the memory back once they resume.
  if (free_bit_sets_.size() >= kMaxSpareBitSets)
    bit_sets_[s.bit_set] = std::vector<uint64_t>();  // frees it (`= {}` would keep its capacity)
  free_bit_sets_.push_back(s.bit_set);
  s.bit_set = kNoBits;
}

void SentViews::queue_acknowledgement(const SnapshotArchive& archive, uint32_t snapshot) {
  if (num_queued_ > 0 && queued_[num_queued_ - 1] == snapshot) return;  // inputs repeat their ack
  if (num_queued_ == queued_.size()) {
    acknowledge(archive, queued_[0]);
    std::copy(queued_.begin() + 1, queued_.end(), queued_.begin());
    --num_queued_;
  }
  queued_[num_queued_++] = snapshot;
}

void SentViews::acknowledge_queued(const SnapshotArchive& archive) {
  for (uint32_t k = 0; k < num_queued_; ++k) acknowledge(archive, queued_[k]);
  num_queued_ = 0;
}

void SentViews::references(const SnapshotArchive& archive, std::span<const wire::AvatarState> view,
                           uint32_t snapshot, std::vector<AvatarReference>& out) const {
  out.assign(view.size(), AvatarReference{});
  // Both lists are sorted by id: one walk finds each avatar's newest acknowledged snapshot. Most
  // come from the same few snapshots, so the archive slot of the last one is kept.
  uint32_t last_n = 0;
  const SnapshotArchive::Slot* a = nullptr;
  size_t k = 0;
  for (size_t i = 0; i < view.size(); ++i) {
    const uint32_t id = view[i].id();
    while (k < newest_.size() && newest_[k].id < id) ++k;
    if (k == newest_.size()) break;
    if (newest_[k].id != id) continue;
    const uint32_t n = newest_[k].snapshot, back = snapshot - n;
    const bool far = newest_[k].far != 0;
    const uint32_t index = newest_[k].index;
    // newest_ holds acknowledged snapshots only, and the slot of one at most 63 back has not been
    // reused (64 slots), so it still says which archived snapshot n was cut from.
    if (back == 0 || back > kMaxReferenceBack) continue;
    if (a == nullptr || n != last_n) {
      last_n = n;
      a = archive.find(slots_[n % slots_.size()].archived_as);
    }
    if (a == nullptr) continue;  // gone from the archive (a receiver served rarely)
    if (index >= a->avatars.size() || a->avatars[index].id() != id) continue;
    const wire::AvatarState* it = &a->avatars[index];
    AvatarReference& r = out[i];
    r.found = true;
    r.snapshot = n;
    r.server_tick = a->server_tick;
    r.state = *it;
    r.state.mutate_flags(static_cast<uint8_t>(it->flags() | (id == owner_ ? kAvatarYours : 0) |
                                              (far ? kAvatarFar : 0)));
  }
}

size_t SentViews::bytes() const {
  size_t n = sizeof(*this) + newest_.capacity() * sizeof(Newest) + bit_sets_.capacity() * sizeof(bit_sets_[0]) +
             free_bit_sets_.capacity();
  for (const auto& b : bit_sets_) n += b.capacity() * sizeof(uint64_t);
  return n;
}

void WholeViewSender::remember(uint32_t snapshot, uint32_t server_tick, std::span<const wire::AvatarState> view) {
  SnapshotArchive::Slot& archived = archive_.start(snapshot, server_tick);
  archived.avatars.assign(view.begin(), view.end());
  indices_.resize(view.size());
  for (size_t i = 0; i < view.size(); ++i) indices_[i] = static_cast<uint32_t>(i);
  views_.record(snapshot, archived, indices_, {});
}

void WholeViewSender::plan(AvatarDeltaEncoder& encoder, std::span<const wire::AvatarState> view, uint32_t snapshot,
                           uint32_t server_tick) {
  views_.references(archive_, view, snapshot, references_);
  encoder.plan(view, snapshot, server_tick, references_);
}

}  // namespace foresight::protocol

#include "protocol/sent_views.hpp"

#include "protocol/protocol.hpp"

#include <algorithm>

namespace foresight::protocol {

SnapshotArchive::Slot& SnapshotArchive::start(uint32_t snapshot, uint32_t server_tick) {
  Slot& s = slots_[snapshot % kSlots];
  s.snapshot = snapshot;
  s.server_tick = server_tick;
  s.valid = true;
  s.avatars.clear();
  return s;
}

const SnapshotArchive::Slot* SnapshotArchive::find(uint32_t snapshot) const {
  const Slot& s = slots_[snapshot % kSlots];
  return s.valid && s.snapshot == snapshot ? &s : nullptr;
}

void SnapshotArchive::reserve(size_t avatars) {
  for (Slot& s : slots_) s.avatars.reserve(avatars);
}

size_t SnapshotArchive::bytes() const {
  size_t n = sizeof(*this);
  for (const Slot& s : slots_) n += s.avatars.capacity() * sizeof(wire::AvatarState);
  return n;
}

void SentViews::record(uint32_t snapshot, size_t archived, std::span<const uint32_t> indices,
                       std::span<const uint8_t> far) {
  Slot& s = slots_[snapshot % SnapshotArchive::kSlots];
  s.snapshot = snapshot;
  s.valid = true;
  s.acknowledged = false;
  s.bits.assign((2 * archived + 63) / 64, 0);
  for (size_t k = 0; k < indices.size(); ++k) {
    const size_t i = indices[k];
    if (i >= archived) continue;
    s.bits[2 * i / 64] |= uint64_t{1} << (2 * i % 64);
    if (k < far.size() && far[k] != 0) s.bits[(2 * i + 1) / 64] |= uint64_t{1} << ((2 * i + 1) % 64);
  }
}

void SentViews::acknowledge(uint32_t snapshot) {
  Slot& s = slots_[snapshot % SnapshotArchive::kSlots];
  if (s.valid && s.snapshot == snapshot) s.acknowledged = true;
}

void SentViews::references(const SnapshotArchive& archive, std::span<const wire::AvatarState> view,
                           uint32_t snapshot, std::vector<AvatarReference>& out) const {
  out.assign(view.size(), AvatarReference{});
  // The acknowledged snapshots in reach, newest first, each with a cursor into its archived
  // avatars (view ids increase, so each cursor only moves forward).
  struct Candidate {
    const Slot* view;
    const SnapshotArchive::Slot* archived;
    size_t cursor;
  };
  std::array<Candidate, SnapshotArchive::kSlots> candidates;
  size_t count = 0;
  for (uint32_t back = 1; back <= kMaxReferenceBack; ++back) {
    const uint32_t n = snapshot - back;
    const Slot& s = slots_[n % SnapshotArchive::kSlots];
    const SnapshotArchive::Slot* a = archive.find(n);
    if (s.valid && s.acknowledged && s.snapshot == n && a != nullptr) candidates[count++] = {&s, a, 0};
  }
  for (size_t i = 0; i < view.size(); ++i) {
    const uint32_t id = view[i].id();
    for (size_t c = 0; c < count; ++c) {
      Candidate& cand = candidates[c];
      const auto& avatars = cand.archived->avatars;
      const auto it = std::lower_bound(avatars.begin() + static_cast<std::ptrdiff_t>(cand.cursor), avatars.end(), id,
                                       [](const wire::AvatarState& a, uint32_t v) { return a.id() < v; });
      cand.cursor = static_cast<size_t>(it - avatars.begin());
      if (it == avatars.end() || it->id() != id) continue;
      const size_t bit = 2 * cand.cursor;
      if (bit / 64 >= cand.view->bits.size() || (cand.view->bits[bit / 64] >> (bit % 64) & 1) == 0) continue;
      const bool far = (cand.view->bits[(bit + 1) / 64] >> ((bit + 1) % 64) & 1) != 0;
      AvatarReference& r = out[i];
      r.found = true;
      r.snapshot = cand.archived->snapshot;
      r.server_tick = cand.archived->server_tick;
      r.state = *it;
      r.state.mutate_flags(static_cast<uint8_t>(it->flags() | (id == owner_ ? kAvatarYours : 0) | (far ? kAvatarFar : 0)));
      break;
    }
  }
}

void SentViews::clear() {
  for (Slot& s : slots_) s.valid = s.acknowledged = false;
}

size_t SentViews::bytes() const {
  size_t n = sizeof(*this);
  for (const Slot& s : slots_) n += s.bits.capacity() * sizeof(uint64_t);
  return n;
}

void WholeViewSender::remember(uint32_t snapshot, uint32_t server_tick, std::span<const wire::AvatarState> view) {
  archive_.start(snapshot, server_tick).avatars.assign(view.begin(), view.end());
  indices_.resize(view.size());
  for (size_t i = 0; i < view.size(); ++i) indices_[i] = static_cast<uint32_t>(i);
  views_.record(snapshot, view.size(), indices_, {});
}

void WholeViewSender::plan(AvatarDeltaEncoder& encoder, std::span<const wire::AvatarState> view, uint32_t snapshot,
                           uint32_t server_tick) {
  views_.references(archive_, view, snapshot, references_);
  encoder.plan(view, snapshot, server_tick, references_);
}

}  // namespace foresight::protocol

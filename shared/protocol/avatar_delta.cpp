#include "protocol/avatar_delta.hpp"

#include <algorithm>
#include <bit>

namespace foresight::protocol {
namespace {

// A difference of more than this many millimetres is sent whole instead (it keeps the zigzag
// code under 2^31).
constexpr int64_t kMaxDeltaMm = int64_t{1} << 29;
// A reference further back than this many server ticks is not used (frame arithmetic stays small).
constexpr uint32_t kMaxRefTicks = 1u << 16;

bool same_playthrough(const wire::AvatarState& a, const wire::AvatarState& r) {
  return a.segment() == r.segment() && a.transition() == r.transition() && a.start_x_mm() == r.start_x_mm() &&
         a.start_z_mm() == r.start_z_mm() && a.start_heading() == r.start_heading();
}

bool delta_fits(const wire::AvatarState& a, const wire::AvatarState& r) {
  const int64_t dx = int64_t{a.start_x_mm()} - r.start_x_mm(), dz = int64_t{a.start_z_mm()} - r.start_z_mm();
  return dx > -kMaxDeltaMm && dx < kMaxDeltaMm && dz > -kMaxDeltaMm && dz < kMaxDeltaMm;
}

bool by_id(const wire::AvatarState& a, uint32_t id) { return a.id() < id; }

int index_bits(int refs) { return refs > 1 ? std::bit_width(static_cast<unsigned>(refs - 1)) : 0; }

}  // namespace

const wire::AvatarState* AvatarHistory::Slot::find(uint32_t id) const {
  const auto it = std::lower_bound(avatars.begin(), avatars.end(), id, by_id);
  return it != avatars.end() && it->id() == id ? &*it : nullptr;
}

AvatarHistory::Slot& AvatarHistory::start(uint32_t snapshot, uint32_t server_tick) {
  Slot& s = slots_[snapshot % kSlots];
  s.snapshot = snapshot;
  s.server_tick = server_tick;
  s.valid = true;
  s.usable = false;
  s.avatars.clear();
  return s;
}

AvatarHistory::Slot* AvatarHistory::find(uint32_t snapshot) {
  Slot& s = slots_[snapshot % kSlots];
  return s.valid && s.snapshot == snapshot ? &s : nullptr;
}

const AvatarHistory::Slot* AvatarHistory::find(uint32_t snapshot) const {
  const Slot& s = slots_[snapshot % kSlots];
  return s.valid && s.snapshot == snapshot ? &s : nullptr;
}

void AvatarHistory::clear() {
  for (Slot& s : slots_) {
    s.valid = s.usable = false;
    s.avatars.clear();
  }
}

void AvatarHistory::reserve(size_t avatars) {
  for (Slot& s : slots_) s.avatars.reserve(avatars);
}

void AvatarDeltaEncoder::plan(std::span<const wire::AvatarState> view, uint32_t snapshot, uint32_t server_tick,
                              std::span<const AvatarReference> references) {
  view_ = view;
  num_refs_ = 0;
  referenced_ = 0;
  ref_of_.assign(view.size(), -1);
  reference_.assign(view.size(), nullptr);
  for (size_t i = 0; i < references.size() && i < view.size(); ++i) {
    const AvatarReference& r = references[i];
    const uint32_t back = snapshot - r.snapshot, ticks = server_tick - r.server_tick;
    if (!r.found || back == 0 || back > kMaxReferenceBack || ticks >= kMaxRefTicks || r.state.id() != view[i].id() ||
        !delta_fits(view[i], r.state))
      continue;
    int ref = 0;
    while (ref < num_refs_ && refs_[static_cast<size_t>(ref)].back != back) ++ref;
    if (ref == num_refs_) {
      if (num_refs_ == static_cast<int>(refs_.size())) continue;  // no index left: whole
      refs_[static_cast<size_t>(num_refs_++)] = {back, ticks};
    }
    ref_of_[i] = static_cast<int8_t>(ref);
    reference_[i] = &r.state;
    ++referenced_;
  }
  index_bits_ = index_bits(num_refs_);
  uint32_t max_segment = 0, max_transition = 0;
  for (const wire::AvatarState& a : view) {
    max_segment = std::max<uint32_t>(max_segment, a.segment());
    max_transition = std::max(max_transition, static_cast<uint32_t>(a.transition()) + 1u);
  }
  segment_bits_ = std::bit_width(max_segment);
  transition_bits_ = std::bit_width(max_transition);
}

void AvatarDeltaEncoder::begin_part(BitWriter& out) {
  out.put(static_cast<uint32_t>(segment_bits_), 5);
  out.put(static_cast<uint32_t>(transition_bits_), 6);
  out.put(static_cast<uint32_t>(num_refs_), 3);
  for (int i = 0; i < num_refs_; ++i) {
    out.put(refs_[static_cast<size_t>(i)].back, 6);
    out.put_gamma(uint64_t{refs_[static_cast<size_t>(i)].ticks} + 1);
  }
  previous_id_ = -1;
}

void AvatarDeltaEncoder::add(size_t index, BitWriter& out) {
  const wire::AvatarState& a = view_[index];
  out.put_gamma(static_cast<uint64_t>(int64_t{a.id()} - previous_id_));
  previous_id_ = a.id();
  const int ref = ref_of_[index];
  if (num_refs_ > 0) {
    out.put_bit(ref >= 0);
    if (ref >= 0) out.put(static_cast<uint32_t>(ref), index_bits_);
  }
  if (ref >= 0) {
    const wire::AvatarState& r = *reference_[index];
    const bool same = same_playthrough(a, r);
    out.put_bit(same);
    if (same) {
      const int32_t predicted = int32_t{r.frame()} + static_cast<int32_t>(refs_[static_cast<size_t>(ref)].ticks);
      const int32_t residual = int32_t{a.frame()} - predicted;  // small: ticks < kMaxRefTicks
      out.put_bit(residual == 0);
      if (residual != 0) out.put_signed_gamma(residual);
    } else {
      out.put(a.segment(), segment_bits_);
      out.put(static_cast<uint32_t>(a.transition()) + 1u, transition_bits_);
      out.put_signed_wide(a.start_x_mm() - r.start_x_mm());
      out.put_signed_wide(a.start_z_mm() - r.start_z_mm());
      out.put_signed_wide(static_cast<int16_t>(static_cast<uint16_t>(a.start_heading() - r.start_heading())));
      out.put_gamma(uint64_t{a.frame()} + 1);
    }
    out.put_bit(a.flags() == r.flags());
    if (a.flags() != r.flags()) out.put(a.flags(), 8);
  } else {
    out.put(a.segment(), segment_bits_);
    out.put(static_cast<uint32_t>(a.transition()) + 1u, transition_bits_);
    out.put_signed_wide(a.start_x_mm());
    out.put_signed_wide(a.start_z_mm());
    out.put(a.start_heading(), 16);
    out.put_gamma(uint64_t{a.frame()} + 1);
    out.put(a.flags(), 8);
  }
  out.put_bit(a.reserved() == 0);
  if (a.reserved() != 0) out.put(a.reserved(), 16);
}

void AvatarDeltaEncoder::write_part(size_t begin, size_t end, std::vector<uint8_t>& out) {
  BitWriter bits(out);
  begin_part(bits);
  for (size_t i = begin; i < end; ++i) add(i, bits);
  bits.finish();
}

AvatarDecodeStatus decode_avatars(std::span<const uint8_t> packed, uint32_t count, uint32_t snapshot,
                                  const AvatarHistory& history, std::vector<wire::AvatarState>& out) {
  BitReader in(packed);
  const int segment_bits = static_cast<int>(in.get(5));
  const int transition_bits = static_cast<int>(in.get(6));
  if (segment_bits > 16 || transition_bits > 32) return AvatarDecodeStatus::kMalformed;
  struct Ref {
    uint32_t ticks = 0;
    const AvatarHistory::Slot* slot = nullptr;
    size_t cursor = 0;  ///< Into slot->avatars: ids come in increasing order, so it only moves on.
  };
  std::array<Ref, 7> refs{};
  const int num_refs = static_cast<int>(in.get(3));
  for (int i = 0; i < num_refs; ++i) {
    const uint32_t back = in.get(6);
    const uint64_t ticks = in.get_gamma();
    if (back == 0 || ticks == 0 || ticks - 1 >= kMaxRefTicks) return AvatarDecodeStatus::kMalformed;
    const AvatarHistory::Slot* s = history.find(snapshot - back);
    refs[static_cast<size_t>(i)] = {static_cast<uint32_t>(ticks - 1), s && s->usable ? s : nullptr};
  }
  const int bits = index_bits(num_refs);
  const size_t first = out.size();
  int64_t previous_id = -1;
  for (uint32_t k = 0; k < count && !in.failed(); ++k) {
    const uint64_t gap = in.get_gamma();  // >= 1; the encoder's largest is 2^32 (from -1 to UINT32_MAX)
    if (gap == 0 || gap > uint64_t{UINT32_MAX} + 1) break;
    const int64_t id = previous_id + static_cast<int64_t>(gap);
    if (id > int64_t{UINT32_MAX}) break;
    previous_id = id;
    int ref = -1;
    if (num_refs > 0 && in.get_bit()) ref = static_cast<int>(in.get(bits));
    if (ref >= num_refs) break;
    uint16_t segment = 0, heading = 0;
    int32_t transition = -1, x = 0, z = 0;
    uint8_t frame = 0, flags = 0;
    if (ref >= 0) {
      Ref& rf = refs[static_cast<size_t>(ref)];
      const wire::AvatarState* r = nullptr;
      if (rf.slot != nullptr) {
        const auto& held = rf.slot->avatars;
        while (rf.cursor < held.size() && held[rf.cursor].id() < id) ++rf.cursor;
        if (rf.cursor < held.size() && held[rf.cursor].id() == id) r = &held[rf.cursor];
      }
      if (!r) {
        out.resize(first);
        return AvatarDecodeStatus::kMissingBaseline;
      }
      if (in.get_bit()) {
        segment = r->segment(), transition = r->transition(), x = r->start_x_mm(), z = r->start_z_mm();
        heading = r->start_heading();
        const int64_t predicted = int64_t{r->frame()} + rf.ticks;
        frame = static_cast<uint8_t>(in.get_bit() ? predicted : predicted + in.get_signed_gamma());
      } else {
        segment = static_cast<uint16_t>(in.get(segment_bits));
        transition = static_cast<int32_t>(in.get(transition_bits) - 1u);
        x = static_cast<int32_t>(static_cast<uint32_t>(r->start_x_mm()) + static_cast<uint32_t>(in.get_signed_wide()));
        z = static_cast<int32_t>(static_cast<uint32_t>(r->start_z_mm()) + static_cast<uint32_t>(in.get_signed_wide()));
        heading = static_cast<uint16_t>(r->start_heading() + static_cast<uint32_t>(in.get_signed_wide()));
        frame = static_cast<uint8_t>(in.get_gamma() - 1);
      }
      flags = in.get_bit() ? r->flags() : static_cast<uint8_t>(in.get(8));
    } else {
      segment = static_cast<uint16_t>(in.get(segment_bits));
      transition = static_cast<int32_t>(in.get(transition_bits) - 1u);
      x = in.get_signed_wide();
      z = in.get_signed_wide();
      heading = static_cast<uint16_t>(in.get(16));
      frame = static_cast<uint8_t>(in.get_gamma() - 1);
      flags = static_cast<uint8_t>(in.get(8));
    }
    const uint16_t reserved = in.get_bit() ? 0 : static_cast<uint16_t>(in.get(16));
    out.emplace_back(static_cast<uint32_t>(id), x, z, transition, segment, heading, frame, flags, reserved);
  }
  // Every avatar read, nothing cut off, and no more than the last byte's padding left over.
  if (in.failed() || out.size() - first != count || in.remaining_bits() >= 8) {
    out.resize(first);
    return AvatarDecodeStatus::kMalformed;
  }
  return AvatarDecodeStatus::kOk;
}

AvatarDecodeStatus snapshot_avatars(const wire::Snapshot& m, const AvatarHistory& history,
                                    std::vector<wire::AvatarState>& out) {
  if (m.avatar_count() == 0) return AvatarDecodeStatus::kOk;
  const auto* bits = m.avatar_bits();
  if (bits == nullptr) return AvatarDecodeStatus::kMalformed;
  return decode_avatars({bits->data(), bits->size()}, m.avatar_count(), m.tick(), history, out);
}

void pack_avatars(std::span<const wire::AvatarState> avatars, std::vector<uint8_t>& out) {
  AvatarDeltaEncoder encoder;
  encoder.plan(avatars, 0, 0, {});
  encoder.write_part(0, avatars.size(), out);
}

}  // namespace foresight::protocol

#include "snapshot_builder.hpp"

#include "protocol/protocol.hpp"

namespace foresight::server {

void SnapshotBuilder::serve(const SnapshotFrame& frame, const SnapshotReceiver& to, protocol::UdpSocket& socket) {
  build_view(frame, to);
  to.sent_views->acknowledge_queued(*frame.archive);
  to.sent_views->references(*frame.archive, view_states_, to.snapshot, references_);
  encoder_.plan(view_states_, to.snapshot, frame.server_tick, references_);
  plan_parts(frame);
  const auto parts = static_cast<uint8_t>(parts_.size());
  for (size_t part = 0; part < parts_.size(); ++part) {
    const Part& plan = parts_[part];
    auto& fbb = writer_.begin();
    const auto avatar_bits = fbb.CreateVector(part_bits_[part]);
    flatbuffers::Offset<flatbuffers::Vector<flatbuffers::Offset<wire::FighterPose>>> fighters = 0;
    if (plan.fighters_end > plan.fighters_begin) {
      fighter_offsets_.clear();
      for (size_t f = plan.fighters_begin; f < plan.fighters_end; ++f) {
        const FighterPoseOut& fp = frame.fighters[f];
        const auto rotations = fbb.CreateVector(frame.fighter_rotations.data() + fp.first_rotation, fp.num_rotations);
        fighter_offsets_.push_back(wire::CreateFighterPose(fbb, fp.avatar, fp.morphology, fp.pelvis_mm[0],
                                                            fp.pelvis_mm[1], fp.pelvis_mm[2], rotations));
      }
      fighters = fbb.CreateVector(fighter_offsets_);
    }
    flatbuffers::Offset<flatbuffers::Vector<const wire::TerrainBody*>> terrain_bodies = 0;
    const uint32_t terrain_begin = view_terrain_before_[plan.avatars_begin];
    const uint32_t terrain_end = view_terrain_before_[plan.avatars_end];
    if (terrain_end > terrain_begin)
      terrain_bodies = fbb.CreateVectorOfStructs(view_terrain_.data() + terrain_begin, terrain_end - terrain_begin);
    flatbuffers::Offset<flatbuffers::Vector<const wire::StrikeEventState*>> events = 0;
    if (plan.events && !frame.events.empty())
      events = fbb.CreateVectorOfStructs(frame.events.data(), frame.events.size());
    const auto inner = writer_.finish(wire::CreateSnapshot(
        fbb, to.snapshot, static_cast<uint8_t>(part), parts, to.ack_input, to.echo_client_time_ms, frame.server_ms,
        fighters, events, terrain_bodies, static_cast<uint16_t>(plan.avatars_end - plan.avatars_begin), avatar_bits));
    batch_.add(socket, to.sealer->seal(seal_writer_, inner), *to.endpoint);
  }
  // What was sent (all of the view unless it ran past the 255 parts), for later references.
  const size_t sent = parts_.back().avatars_end;
  to.sent_views->record(to.snapshot, *frame.archived, std::span(view_index_).first(sent),
                        std::span(view_far_).first(sent));
  avatars_sent_ += sent;
  avatars_referenced_ += encoder_.referenced();
}

SnapshotBuilder::Counts SnapshotBuilder::take_counts() {
  Counts c{avatars_sent_, avatars_referenced_, batch_.take_counts()};
  avatars_sent_ = avatars_referenced_ = 0;
  return c;
}

// What one client gets (interest.hpp): the avatars near its own every snapshot, the far ones when
// due (flagged kAvatarFar), its own flagged kAvatarYours; their terrain bodies with them.
void SnapshotBuilder::build_view(const SnapshotFrame& frame, const SnapshotReceiver& to) {
  const auto n = static_cast<uint32_t>(frame.states.size());
  if (frame.interest != nullptr) {
    select_interest(*frame.interest, frame.positions, to.index, frame.interest_radius_m, to.far_due, frame.far_radius_m,
                    view_index_, view_far_);
  } else {
    view_index_.resize(n);
    for (uint32_t i = 0; i < n; ++i) view_index_[i] = i;
    view_far_.assign(n, 0);
  }
  view_states_.clear();
  view_terrain_.clear();
  view_terrain_before_.clear();
  for (size_t k = 0; k < view_index_.size(); ++k) {
    const uint32_t i = view_index_[k];
    view_terrain_before_.push_back(static_cast<uint32_t>(view_terrain_.size()));
    wire::AvatarState a = frame.states[i];
    a.mutate_flags(static_cast<uint8_t>(a.flags() | (i == to.index ? protocol::kAvatarYours : 0) |
                                        (view_far_[k] ? protocol::kAvatarFar : 0)));
    view_states_.push_back(a);
    for (uint32_t t = frame.terrain_before[i]; t < frame.terrain_before[i + 1]; ++t) view_terrain_.push_back(frame.terrain[t]);
  }
  view_terrain_before_.push_back(static_cast<uint32_t>(view_terrain_.size()));
}

// Parts of one client's view under the datagram budget: fighters' poses first, the strike events
// in part 0, then the avatars, packed (avatar_delta.hpp) into part_bits_ as they are planned.
// Sizes are upper bounds of what FlatBuffers writes (tables: vtable and alignment).
void SnapshotBuilder::plan_parts(const SnapshotFrame& frame) {
  // Header, vectors, Snapshot table, and the Sealed wrapping around it.
  constexpr size_t kBudget = protocol::kMaxDatagramBytes - 100 - protocol::kSealOverheadBytes;
  parts_.clear();
  size_t fighter = 0, avatar = 0;
  do {
    Part part;
    part.events = parts_.empty();
    size_t bytes = part.events ? frame.events.size() * sizeof(wire::StrikeEventState) : 0;
    part.fighters_begin = fighter;
    while (fighter < frame.fighters.size() && bytes + 64 + 4 * frame.fighters[fighter].num_rotations <= kBudget)
      bytes += 64 + 4 * frame.fighters[fighter++].num_rotations;
    part.fighters_end = fighter;
    part.avatars_begin = avatar;
    if (part_bits_.size() <= parts_.size()) part_bits_.resize(parts_.size() + 1);
    protocol::BitWriter bits(part_bits_[parts_.size()]);
    encoder_.begin_part(bits);
    while (avatar < view_states_.size() && avatar - part.avatars_begin < UINT16_MAX) {
      const size_t body = (view_terrain_before_[avatar + 1] - view_terrain_before_[avatar]) * sizeof(wire::TerrainBody);
      if (bytes + bits.bytes() + protocol::AvatarDeltaEncoder::kMaxAvatarBytes + body > kBudget) break;
      encoder_.add(avatar, bits);
      bytes += body;
      ++avatar;
    }
    bits.finish();
    part.avatars_end = avatar;
    parts_.push_back(part);
  } while ((fighter < frame.fighters.size() || avatar < view_states_.size()) && parts_.size() < 255);
}

}  // namespace foresight::server

#pragma once
// The snapshot phase's per-client work (docs/SERVER.md "The tick"): one client's view of the
// snapshot (interest), its avatars delta-coded against what it acknowledged, cut into datagrams
// under the size budget, sealed and sent. The tick thread gathers the snapshot once
// (SnapshotFrame, read-only while clients are served); the look-ahead workers then serve the
// clients in parallel, each worker with its own SnapshotBuilder (scratch, writers and a
// sendmmsg batch), so nothing is shared but the frame and the socket's descriptor.
#include "interest.hpp"
#include "protocol/avatar_delta.hpp"
#include "transport/datagram_batch.hpp"
#include "protocol/packet.hpp"
#include "protocol/sent_views.hpp"
#include "transport/session_crypto.hpp"
#include "transport/udp_socket.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace foresight::server {

/// A fighter's pose in the snapshot: its rotations are a run of SnapshotFrame::fighter_rotations.
struct FighterPoseOut {
  uint32_t avatar = 0;
  uint8_t morphology = 0;
  int32_t pelvis_mm[3] = {0, 0, 0};
  size_t first_rotation = 0, num_rotations = 0;
};

/// One snapshot, as every client's view is cut from it.
struct SnapshotFrame {
  uint32_t server_tick = 0;
  uint32_t server_ms = 0;
  std::span<const wire::AvatarState> states;   ///< Every avatar, by id (world flags).
  std::span<const vec2> positions;             ///< Per avatar: where it stands (interest).
  std::span<const wire::TerrainBody> terrain;  ///< Terrain avatars' bodies, in avatar order.
  std::span<const uint32_t> terrain_before;    ///< Per avatar (and one past): bodies before it.
  std::span<const FighterPoseOut> fighters;
  std::span<const uint32_t> fighter_rotations;
  std::span<const wire::StrikeEventState> events;
  const InterestGrid* interest = nullptr;  ///< Built with interest_radius_m; nullptr: everyone.
  float interest_radius_m = 0, far_radius_m = 0;
  const protocol::SnapshotArchive::Slot* archived = nullptr;  ///< This snapshot in the archive.
  const protocol::SnapshotArchive* archive = nullptr;          ///< It and the ones before.
};

/// One client the snapshot goes to; a client is served by one worker at a time.
struct SnapshotReceiver {
  uint32_t snapshot = 0;  ///< Snapshot::tick: its own count of the snapshots it got, one up each.
  uint32_t index = 0;     ///< Its own avatar in SnapshotFrame::states.
  uint32_t avatar_id = 0;
  uint32_t ack_input = 0;
  uint32_t echo_client_time_ms = 0;
  bool far_due = false;  ///< Its far avatars go in this one (interest.hpp).
  const protocol::Endpoint* endpoint = nullptr;
  protocol::Sealer* sealer = nullptr;
  protocol::SentViews* sent_views = nullptr;
};

class SnapshotBuilder {
 public:
  /// Builds, seals and queues (sends when its batch fills) `to`'s snapshot.
  void serve(const SnapshotFrame& frame, const SnapshotReceiver& to, protocol::UdpSocket& socket);
  /// Sends what is still queued.
  void flush(protocol::UdpSocket& socket) { batch_.flush(socket); }

  struct Counts {
    uint64_t avatars_sent = 0, avatars_referenced = 0;
    protocol::DatagramBatch::Counts datagrams;
  };
  /// What was sent since the last call.
  Counts take_counts();

 private:
  struct Part {
    size_t fighters_begin = 0, fighters_end = 0, avatars_begin = 0, avatars_end = 0;
    bool events = false;
  };
  void build_view(const SnapshotFrame& frame, const SnapshotReceiver& to);
  void plan_parts(const SnapshotFrame& frame);

  std::vector<uint32_t> view_index_;
  std::vector<uint8_t> view_far_;
  std::vector<wire::AvatarState> view_states_;
  std::vector<wire::TerrainBody> view_terrain_;
  std::vector<uint32_t> view_terrain_before_;
  std::vector<protocol::AvatarReference> references_;
  protocol::AvatarDeltaEncoder encoder_;
  std::vector<Part> parts_;
  std::vector<std::vector<uint8_t>> part_bits_;  ///< Per part, its packed avatars.
  std::vector<flatbuffers::Offset<wire::FighterPose>> fighter_offsets_;
  protocol::PacketWriter writer_;
  protocol::PacketWriter seal_writer_;
  protocol::DatagramBatch batch_;
  uint64_t avatars_sent_ = 0, avatars_referenced_ = 0;
};

}  // namespace foresight::server

#pragma once
// Protocol constants shared by server, client and bots (schema/foresight.fbs, docs/PROTOCOL.md).
#include <cstddef>
#include <cstdint>

namespace foresight::protocol {

/// Bumped whenever a peer of the previous version could misread a message.
inline constexpr uint32_t kProtocolVersion = 8;  // 2: TreeNodeSample carries segment, heading; 3: fighters; 4: terrain bodies; 5: sealed sessions; 6: packed avatars; 7: scenes sent to clients; 8: packed-avatar references reach 63 snapshots back (6 bits)

/// Largest datagram anyone sends: under the common 1280-byte IPv6 minimum MTU after headers, so
/// nothing is ever fragmented.
inline constexpr size_t kMaxDatagramBytes = 1200;
/// A ConnectRequest must be at least this big (padding): the Challenge it triggers is smaller,
/// so a spoofed source address cannot use the server as an amplifier.
inline constexpr size_t kMinConnectRequestBytes = 160;
/// Commands repeated in every Input packet: a loss of up to this many packets in a row loses
/// no command.
inline constexpr int kInputRedundancy = 8;
/// Verifier limits for received buffers (the schema nests 3 tables deep at most).
inline constexpr int kVerifierMaxDepth = 8;
inline constexpr int kVerifierMaxTables = 64;

/// AvatarState::flags bits.
enum AvatarFlags : uint8_t {
  kAvatarNone = 0,
  kAvatarYours = 1u << 0,     ///< The receiving client's own avatar.
  kAvatarFallback = 1u << 1,  ///< Stopped: nothing feasible ahead (idle fallback).
  kAvatarNpc = 1u << 2,       ///< Server-controlled.
  kAvatarStriking = 1u << 3,  ///< An NPC fighter between the start of a strike and its end.
  /// Walks by the terrain planners: no segment; start_x/z and start_heading are where its pelvis
  /// stands now, its body is the snapshot's TerrainBody with the same id.
  kAvatarTerrain = 1u << 4,
  /// Beyond the receiver's interest radius: it comes only every few snapshots (the client keeps
  /// showing it in between).
  kAvatarFar = 1u << 5,
};
/// AvatarState::segment of a terrain avatar.
inline constexpr uint16_t kNoSegment = 0xFFFF;
/// TerrainBody::angles: radians per unit.
inline constexpr float kTerrainAngleUnitRad = 1e-4f;
/// TerrainBody::flags bits.
enum TerrainBodyFlags : uint8_t {
  kTerrainWalking = 1u << 0,
  kTerrainPivoting = 1u << 1,
};

/// Fighters' poses: at most this many joints are sent (the default skeleton has fewer).
inline constexpr size_t kMaxFighterJoints = 64;
/// A strike event is repeated in the snapshots of this many ticks after it (1 s at 30 Hz).
inline constexpr uint32_t kStrikeEventRepeatTicks = 30;

/// Most nodes one TreeSummary samples: 12 bytes each (since they carry segment and heading for
/// ghost poses; 128 when they were 8; 80 since sessions are sealed), so a full summary stays under
/// kMaxDatagramBytes inside its Sealed wrapping.
inline constexpr size_t kMaxTreeSamples = 80;
/// TreeNodeSample::parent of the root.
inline constexpr uint16_t kTreeNoParent = 0xFFFF;
/// TreeNodeSample::flags bits.
enum TreeNodeFlags : uint8_t {
  kTreeNodeChosen = 1u << 0,  ///< On the branch the tree would select now.
};

}  // namespace foresight::protocol

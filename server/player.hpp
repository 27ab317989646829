#pragma once
// One avatar and whoever drives it: a client's session, or an NPC fighter (no endpoint, never
// times out). Private to the server's translation units.
#include "fighters/fighter_npc.hpp"
#include "lookahead/lookahead_avatar.hpp"
#include "transport/udp_socket.hpp"
#include "terrain/terrain_avatar.hpp"
#include "server.hpp"

#include <memory>
#include <string>

namespace foresight::server {

struct Server::Player {
  protocol::Endpoint endpoint;
  uint32_t session = 0;
  uint32_t avatar_id = 0;
  std::string name;
  std::unique_ptr<LookaheadAvatar> avatar;          ///< Motion-graph avatars (and fighters).
  std::unique_ptr<terrain::TerrainAvatar> terrain;  ///< Terrain avatars (Locomotion::kTerrain).
  std::unique_ptr<FighterNpc> fighter;  ///< Set for NPC fighters.
  Clock::time_point last_heard{};
  bool any_input = false;
  uint32_t last_input_seq = 0;  ///< Newest command applied.
  ControlInput input;  ///< The command the player holds (applied in the look-ahead phase).
  bool input_changed = true;
  /// Which archived avatars went into the last snapshots sent, and which of those snapshots the
  /// client acknowledged (sent_views.hpp).
  protocol::SentViews sent_views;
  uint32_t echo_client_time_ms = 0;
  double tokens = 0;            ///< Packet rate limit (token bucket).
  // The session's keys: what we send is sealed, what it sends is opened (session_crypto.hpp).
  protocol::Sealer sealer;
  protocol::Opener opener;
  protocol::SessionKey server_public_key{};
  Clock::time_point tokens_at{};

  bool is_fighter() const { return fighter != nullptr; }
};

}  // namespace foresight::server

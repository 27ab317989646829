#pragma once
// Counters an operator (/metrics, /status) and the tests read; every stage adds to them.
#include "protocol/packet.hpp"

#include <cstdint>

namespace foresight::server {

/// Counters an operator (and the tests) read.
struct ServerCounters {
  uint64_t packets_in = 0;
  uint64_t bytes_in = 0;
  uint64_t packets_out = 0;
  uint64_t bytes_out = 0;
  uint64_t send_failures = 0;
  uint64_t challenges_sent = 0;
  uint64_t challenges_capped = 0;   ///< Connect requests ignored: over max_challenges_per_tick.
  uint64_t sessions_opened = 0;
  uint64_t joins_deferred = 0;      ///< Verified joins that had to queue (max_joins_per_tick).
  uint64_t sessions_timed_out = 0;
  uint64_t sessions_closed = 0;     ///< Clean disconnects.
  uint64_t refused = 0;             ///< Refuse messages sent (library, version, full, cookie).
  uint64_t spawn_refusals = 0;      ///< Of those, joins with no free place near the spawns.
  uint64_t scene_parts_sent = 0;    ///< ScenePart answers to clients fetching the scene file.
  uint64_t avatar_contacts = 0;     ///< Ticks with two avatars' bodies overlapping (must stay 0).
  uint64_t fallbacks = 0;
  uint64_t steered_frames = 0;      ///< Frames steering mode turned an avatar's playing motion.
  uint64_t recoveries = 0;          ///< Times steering mode found an avatar wedged and backed it off.
  uint64_t fighter_strikes = 0;     ///< Strikes judged.
  uint64_t fighter_hits = 0;
  uint64_t fighter_strike_failures = 0;  ///< Decided but not startable (logged).
  uint64_t fighter_route_failures = 0;   ///< No route around the walls to a fighter's target.
  uint64_t terrain_steps = 0;     ///< Steps terrain avatars committed.
  uint64_t terrain_pivots = 0;    ///< Turns on the spot.
  uint64_t terrain_refusals = 0;  ///< Plans that failed or were vetoed (the avatar stood).
  uint64_t avatars_sent = 0;        ///< Avatar states in snapshots, over all clients.
  uint64_t avatars_referenced = 0;  ///< Of those, delta-coded against an acknowledged snapshot.
  protocol::DropCounters drops;
};

}  // namespace foresight::server

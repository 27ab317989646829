// Terrain avatars in the tick (issue 7, docs/TERRAIN.md "In the game"): each plays one frame per
// tick and, where its step ends, plans the next one toward its player's direction, keeping clear
// of the other terrain avatars (their pelvis now and where their step ends). The time goes into
// the tick's advance phase, so the look-ahead budget of the tree avatars (if any) shrinks by it.
#include "server.hpp"

#include "protocol/protocol.hpp"
#include "protocol/quantize.hpp"
#include "world/terrain.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace foresight::server {

namespace {

int16_t quantize_terrain_angle(float rad) {
  return static_cast<int16_t>(std::clamp(std::lround(rad / protocol::kTerrainAngleUnitRad), -32767l, 32767l));
}

}  // namespace

bool Server::terrain_place_free(const Placement& place) const {
  float ground_y = 0.0f;
  if (!terrain_height_at(scene_.terrain, place.pos_m, ground_y)) return false;
  // Standing there: the body upright, arms hanging, clear of the boxes; nobody within reach.
  const terrain::TerrainBodyPose body = terrain::terrain_body_standing(
      terrain_config_.walker.footsteps.walk, terrain_config_.walker.upper_body.body, place.pos_m, ground_y,
      place.heading_rad);
  const terrain::PelvisFrame frame{body.pelvis_m, place.heading_rad, 0.0f, 0.0f};
  terrain::UpperBodyObstacles obstacles;
  terrain::gather_upper_body_obstacles(scene_, std::span(&frame, 1), 1.0f, 0.0f, obstacles);
  if (obstacles.overflow || !terrain::upper_body_clear(terrain_config_.walker.upper_body.body, frame, body.upper, obstacles))
    return false;
  for (const TerrainWalker& w : terrain_walkers_.items()) {
    for (vec2 other : {terrain::terrain_avatar_ground(*w.avatar), w.avatar->step_end_m})
      if (glm::length(other - place.pos_m) < terrain_config_.personal_space_m + 0.3f) return false;
  }
  return true;
}

void Server::advance_terrain(TickRecord& record) {
  if (!terrain_mode_) return;
  const auto start = std::chrono::steady_clock::now();
  for (TerrainWalker& w : terrain_walkers_.items()) {
    terrain::TerrainAvatar& a = *w.avatar;
    terrain_neighbours_.clear();
    if (terrain::terrain_avatar_may_plan(a)) {
      // Only those a step could reach (at most s_max per step, and their own step).
      const vec2 at = terrain::terrain_avatar_ground(a);
      for (const TerrainWalker& o : terrain_walkers_.items()) {
        if (&o == &w) continue;
        const terrain::TerrainNeighbour n{terrain::terrain_avatar_ground(*o.avatar), o.avatar->step_end_m};
        if (glm::length(n.now_m - at) < 3.0f) terrain_neighbours_.push_back(n);
      }
    }
    const int steps = a.steps, pivots = a.pivots, refusals = a.refusals;
    const vec2 direction = control_input_valid(w.input) ? control_world_direction(w.input) : vec2(0.0f);
    if (terrain::terrain_avatar_frame(a, scene_, direction, terrain_neighbours_)) ++record.terrain_plans;
    counters_.terrain_steps += static_cast<uint64_t>(a.steps - steps);
    counters_.terrain_pivots += static_cast<uint64_t>(a.pivots - pivots);
    counters_.terrain_refusals += static_cast<uint64_t>(a.refusals - refusals);
  }
  record.terrain_ms = static_cast<float>(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
}

void Server::collect_terrain_body(const TerrainWalker& w) {
  const terrain::TerrainAvatar& a = *w.avatar;
  const terrain::TerrainBodyPose& b = a.body;
  const uint16_t heading = protocol::quantize_angle(b.heading_rad);
  const bool standing_refused = !a.stepping && !a.pivoting && a.wait_frames > 0;
  snapshot_states_.emplace_back(w.id, protocol::quantize_mm(b.pelvis_m.x), protocol::quantize_mm(b.pelvis_m.z), -1,
                                protocol::kNoSegment, heading, 0,
                                static_cast<uint8_t>(protocol::kAvatarTerrain |
                                                     (standing_refused ? protocol::kAvatarFallback : protocol::kAvatarNone)),
                                0);
  const auto angles = terrain::terrain_body_angles(b);
  std::array<int16_t, terrain::kTerrainBodyAngles> q;
  for (size_t i = 0; i < q.size(); ++i) q[i] = quantize_terrain_angle(angles[i]);
  snapshot_terrain_.emplace_back(
      w.id, protocol::quantize_mm(b.pelvis_m.x), protocol::quantize_mm(b.pelvis_m.y),
      protocol::quantize_mm(b.pelvis_m.z), heading, static_cast<uint8_t>(a.last_status),
      static_cast<uint8_t>((a.stepping ? protocol::kTerrainWalking : 0) | (a.pivoting ? protocol::kTerrainPivoting : 0)),
      flatbuffers::span<const int16_t, terrain::kTerrainBodyAngles>(q));
}

}  // namespace foresight::server

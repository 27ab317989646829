#include "collision_watch.hpp"

#include "protocol/avatar_state.hpp"

#include <cstdio>

namespace foresight::bots {

CollisionWatch::CollisionWatch(float contact_distance_m) : contact_distance_m_(contact_distance_m) {
  roots_.reserve(1024);
}

void CollisionWatch::observe(const MotionLibrary& library, const Scene& scene, const CollisionWorld& world,
                             const protocol::ClientConnection& connection) {
  if (!connection.has_snapshot()) return;
  if (!has_tick_ || connection.snapshot_tick() != tick_) {
    has_tick_ = true;
    tick_ = connection.snapshot_tick();
    checked_ = 0;
    terrain_checked_ = 0;
    roots_.clear();
    ++ticks_checked_;
  }
  const auto avatars = connection.avatars();
  // Parts are appended as they arrive: only the avatars after checked_ are new.
  for (; checked_ < avatars.size(); ++checked_) {
    if (avatars[checked_].flags() & protocol::kAvatarTerrain) {  // its body is checked below
      Placement root;
      protocol::avatar_root(library, avatars[checked_], root);
      add_root(root.pos_m);
      continue;
    }
    PlaybackState state;
    if (!protocol::avatar_playback(library, avatars[checked_], state)) {
      ++invalid_states_;
      continue;
    }
    ++avatars_checked_;
    if (shown_pose_collides(library, world, state, scratch_, kSceneTolerance_m)) {
      // The first few are described, so a collision can be replayed and understood.
      if (++scene_collisions_ <= 5) {
        const Placement root = playback_root(library, state);
        std::fprintf(stderr,
                     "foresight-bots: avatar %u collides with the scene in snapshot %u: segment '%s' frame %d "
                     "(entered by transition %d), root (%.3f, %.3f) heading %.1f deg\n",
                     avatars[checked_].id(), tick_, library.graph.segments[static_cast<size_t>(state.segment)].name.c_str(),
                     state.frame, state.incoming_transition, root.pos_m.x, root.pos_m.y, degrees(root.heading_rad));
      }
    }
    add_root(playback_root(library, state).pos_m);
  }
  terrain::UpperBodyParams body;
  body.margin_m = 0.0f;
  const auto bodies = connection.terrain_bodies();
  for (; terrain_checked_ < bodies.size(); ++terrain_checked_) {
    const protocol::TerrainBodyState& b = bodies[terrain_checked_];
    terrain::TerrainBodyPose pose;
    terrain::terrain_body_set_angles(pose, b.angles_rad);
    const terrain::PelvisFrame frame{b.pelvis_m, b.heading_rad, 0.0f, 0.0f};
    terrain::gather_upper_body_obstacles(scene, std::span(&frame, 1), 1.5f, 0.0f, obstacles_);
    ++avatars_checked_;
    if (!obstacles_.overflow && !terrain::upper_body_clear(body, frame, pose.upper, obstacles_) &&
        ++scene_collisions_ <= 5)
      std::fprintf(stderr, "foresight-bots: terrain avatar %u's upper body touches the scene in snapshot %u at (%.3f, %.3f)\n",
                   b.avatar, tick_, b.pelvis_m.x, b.pelvis_m.z);
  }
}

void CollisionWatch::add_root(vec2 root) {
  const float d2_limit = contact_distance_m_ * contact_distance_m_;
  for (const vec2& other : roots_) {
    const vec2 d = root - other;
    if (glm::dot(d, d) < d2_limit) ++avatar_contacts_;
  }
  roots_.push_back(root);
}

}  // namespace foresight::bots

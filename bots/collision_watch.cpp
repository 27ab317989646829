#include "collision_watch.hpp"

#include "protocol/avatar_state.hpp"

#include <cstdio>

namespace foresight::bots {

CollisionWatch::CollisionWatch(float contact_distance_m) : contact_distance_m_(contact_distance_m) {
  roots_.reserve(1024);
}

void CollisionWatch::observe(const MotionLibrary& library, const CollisionWorld& world,
                             const protocol::ClientConnection& connection) {
  if (!connection.has_snapshot()) return;
  if (!has_tick_ || connection.snapshot_tick() != tick_) {
    has_tick_ = true;
    tick_ = connection.snapshot_tick();
    checked_ = 0;
    roots_.clear();
    ++ticks_checked_;
  }
  const auto avatars = connection.avatars();
  const float d2_limit = contact_distance_m_ * contact_distance_m_;
  // Parts are appended as they arrive: only the avatars after checked_ are new.
  for (; checked_ < avatars.size(); ++checked_) {
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
    const vec2 root = playback_root(library, state).pos_m;
    for (const vec2& other : roots_) {
      const vec2 d = root - other;
      if (glm::dot(d, d) < d2_limit) ++avatar_contacts_;
    }
    roots_.push_back(root);
  }
}

}  // namespace foresight::bots

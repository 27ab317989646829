#pragma once
// Independent collision check of what a client sees: every avatar of every snapshot tick is
// rebuilt from our copy of the motion library and tested
//  * against the scene: the FK pose actually shown (library/pose_check.hpp), and
//  * against the other avatars of the same tick: roots closer than contact_distance_m.
// A terrain avatar (no clip: its body comes as 16 angles) is tested with the upper-body model the
// server planned it with (terrain/upper_body.hpp, without its 1 cm margin) against the scene's
// boxes; its legs are not checked here.
// Each (tick, avatar) and each (tick, pair) is examined once, as the tick's parts arrive. One
// watch per process (the bots give it one client's view), so events are not counted N times.
//
// Positions and headings arrive quantised (1 mm, 1/65536 turn): a pose that grazes a wall on the
// server can read as touching it here (seen in the load test: a side step passing a wall corner
// with under 5 mm to spare). Scene overlaps therefore count beyond kSceneTolerance_m, the "small
// tolerance" of the issue.
#include "foresight_generated.h"
#include "library/pose_check.hpp"
#include "transport/client_connection.hpp"
#include "terrain/terrain_body.hpp"
#include "world/scene.hpp"
#include "world/collision_world.hpp"

#include <cstdint>
#include <vector>

namespace foresight::bots {

inline constexpr float kSceneTolerance_m = 0.01f;

class CollisionWatch {
 public:
  explicit CollisionWatch(float contact_distance_m = 0.3f);

  /// Examines the avatars of `connection`'s newest snapshot that this watch has not seen yet.
  /// `world` is the scene the server named in its Accept. No allocation once warm.
  void observe(const MotionLibrary& library, const Scene& scene, const CollisionWorld& world,
               const protocol::ClientConnection& connection);

  /// Forget the tick being examined: the next observe() starts it afresh. Call when the watch
  /// is given another client's view (its avatars come in another order).
  void restart() { has_tick_ = false; }

  uint64_t scene_collisions() const { return scene_collisions_; }  ///< (tick, avatar) events.
  uint64_t avatar_contacts() const { return avatar_contacts_; }    ///< (tick, pair) events.
  uint64_t avatars_checked() const { return avatars_checked_; }
  uint64_t ticks_checked() const { return ticks_checked_; }
  uint64_t invalid_states() const { return invalid_states_; }  ///< Not in our library.

 private:
  void add_root(vec2 root);

  float contact_distance_m_;
  bool has_tick_ = false;
  uint32_t tick_ = 0;
  size_t checked_ = 0;       ///< Avatars of tick_ already examined.
  size_t terrain_checked_ = 0;  ///< Terrain bodies of tick_ already examined.
  std::vector<vec2> roots_;  ///< Their root positions, for the pair test.
  PoseCheckScratch scratch_;
  terrain::UpperBodyObstacles obstacles_;
  uint64_t scene_collisions_ = 0, avatar_contacts_ = 0, avatars_checked_ = 0;
  uint64_t ticks_checked_ = 0, invalid_states_ = 0;
};

}  // namespace foresight::bots

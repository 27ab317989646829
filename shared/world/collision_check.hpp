#pragma once
// Collision queries against a CollisionWorld (model: collision_world.hpp, docs/SCENES.md).
// All functions are allocation-free, never throw, and are safe to call from many threads on the
// same world and shapes.
#include "world/body_volume.hpp"
#include "world/collision_world.hpp"
#include "world/segment_shape.hpp"

#include <cstdint>

namespace foresight {

/// Counters a caller may accumulate over many checks (added to, never reset, by the checks).
struct CheckStats {
  std::uint64_t clip_checks = 0;       ///< segment_feasible calls.
  std::uint64_t frame_checks = 0;      ///< Frames actually tested against the scene.
  std::uint64_t sweep_early_outs = 0;  ///< Clips found feasible by the whole-sweep test alone.
  std::uint64_t feasible_clips = 0;
};

/// One frame: true when the volume (world space, y already at its world height) is outside the
/// bounds, over no ground or ground more than the tolerance away from ground_ref_y_m, or overlaps
/// a box.
bool frame_collides(const CollisionWorld& world, const BodyVolume& world_volume,
                    float ground_ref_y_m = 0.0f);

/// The bounds and box part of frame_collides, without the terrain rule: does the volume (world
/// space) leave the bounds or overlap a box?
bool volume_hits_boxes(const CollisionWorld& world, const BodyVolume& world_volume);

/// True only if every frame of the segment placed at `start` is collision-free. The clip is played
/// at the ground height under start.pos_m (h0): each frame's y range is offset by h0 and h0 is the
/// terrain rule's reference; no ground under the start means infeasible. Stops at the first
/// colliding frame. A shape with no frames is feasible when the start has ground.
bool segment_feasible(const CollisionWorld& world, const SegmentCollisionShape& shape,
                      const Placement& start, CheckStats* stats = nullptr);

/// For debugging overlays: the first colliding frame in time order (index into shape.frames),
/// -1 when the segment is feasible, 0 when the start has no ground.
int segment_first_collision(const CollisionWorld& world, const SegmentCollisionShape& shape,
                            const Placement& start);

}  // namespace foresight

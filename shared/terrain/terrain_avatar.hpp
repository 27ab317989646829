#pragma once
// A player's avatar on terrain (docs/TERRAIN.md "In the game"): the TerrainWalker steered by a
// direction on the ground, one animation frame per call.
//
// At the end of each step the next window is planned along a path that keeps everything already
// walked where it is (ground_path_steer: the rear foot, the stance foot and the pelvis between them
// lie on the walked path) and then turns toward the wanted direction, at most max_turn_per_step_rad
// per step, spread over one neutral step. Only the window's first step is played. An avatar that
// stands (it stopped, or was refused) and is steered more than pivot_threshold_rad away from its
// heading first turns on the spot to face the direction, feet brought together (the one motion the
// sagittal walk cannot make: it slides the feet, as games' turn-in-place does). A zero direction
// stops the avatar at the end of the step it is in. When a plan fails (footsteps or upper body) or
// the veto refuses it (another avatar in the way), the avatar stands where it is and tries again
// after retry_frames: by then the player may have steered elsewhere (paper 3.2).
#include "terrain/terrain_body.hpp"
#include "terrain/terrain_walker.hpp"

#include <span>

namespace foresight::terrain {

/// The body's footprint on the ground (a disc around the pelvis), for contact checks.
inline constexpr float kTerrainBodyRadius_m = 0.25f;

struct TerrainAvatarConfig {
  TerrainWalkerConfig walker;
  float max_turn_per_step_rad = 0.5f;
  float lead_m = 0.3f;      ///< Profile behind the rear foot (its heel).
  float look_ahead_m = 3.4f;  ///< Profile beyond the stance foot: n steps of s_max and a foot.
  int retry_frames = 6;     ///< After a refused step, frames before the next try.
  float personal_space_m = 0.6f;  ///< Closest another avatar's pelvis may be, on the ground.
  float pivot_threshold_rad = 0.15f;  ///< A standing avatar turns on the spot beyond this.
  float pivot_speed_radps = 4.0f;     ///< How fast it turns on the spot (90 degrees in 0.4 s).
};

/// Where the other avatars are: their pelvis now and where their committed step ends.
struct TerrainNeighbour {
  vec2 now_m{0.0f};
  vec2 step_end_m{0.0f};
};

/// Fixed workspace: terrain_avatar_init is its only allocation.
struct TerrainAvatar {
  TerrainAvatarConfig config;
  TerrainWalker walker;
  // The committed step being played: frames 0..step_frames, frame 0 the pose it started from.
  WalkStep step{};
  GroundPath step_path;
  std::array<UpperBodyConfig, kMaxUpperBodyFrames> step_upper{};
  bool step_swing_left = true;
  int step_frames = 0;
  int frame = 0;
  bool stepping = false;
  // A turn on the spot in progress: the body blended from pivot_from to pivot_to.
  TerrainBodyPose pivot_from, pivot_to;
  int pivot_frames = 0;
  int pivot_frame = 0;
  bool pivoting = false;
  vec2 step_end_m{0.0f};  ///< Pelvis on the ground where the step in progress ends (or now).
  TerrainBodyPose body;  ///< Shown now.
  TerrainStepStatus last_status = TerrainStepStatus::kOk;  ///< Of the last try (kOk also for a veto).
  bool vetoed = false;  ///< The last try was refused for another avatar.
  int wait_frames = 0;
  // Counters.
  int steps = 0;
  int pivots = 0;
  int refusals = 0;  ///< Plans (or turns on the spot) that failed or were vetoed.
};

/// Stands the avatar at `ground_m` facing heading_rad. False: bad config, or no ground there.
bool terrain_avatar_init(TerrainAvatar& avatar, const TerrainAvatarConfig& config, const Scene& scene, vec2 ground_m,
                         float heading_rad);

/// One frame: plays the step in progress, and where it ends (or the avatar stands) plans the next
/// one toward `direction` (world ground, zero = stop; non-finite counts as zero). `others` are the
/// avatars to keep clear of. True when it planned this frame (what the tick's budget accounts).
bool terrain_avatar_frame(TerrainAvatar& avatar, const Scene& scene, vec2 direction,
                          std::span<const TerrainNeighbour> others);

/// True when the next terrain_avatar_frame may plan (a step ends, or the avatar stands): the
/// only frames that need the neighbours.
inline bool terrain_avatar_may_plan(const TerrainAvatar& a) {
  return a.stepping ? a.frame + 1 >= a.step_frames : !a.pivoting || a.pivot_frame + 1 >= a.pivot_frames;
}
/// Where the pelvis is, on the ground.
inline vec2 terrain_avatar_ground(const TerrainAvatar& avatar) { return ground(avatar.body.pelvis_m); }

}  // namespace foresight::terrain

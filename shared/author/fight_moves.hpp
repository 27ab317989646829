#pragma once
// The fighting moves: the guard stance, idle <-> stance transitions, and parametric punches and
// kicks. Every strike starts and ends exactly in the stance pose (it is the stance plus layers
// whose weights are zero at both ends), and carries where and when it hits.
#include "author/gait.hpp"

#include <optional>
#include <string>
#include <vector>

namespace foresight::author {

/// Where and when a strike lands (see default_library.hpp for the public form).
struct StrikeSpec {
  std::string name;
  std::string kind;    ///< "punch" or "kick"
  int side = kLeft;    ///< Striking hand / foot.
  std::string height;  ///< "low", "mid", "high"
  /// Wrist (punch) or ankle (kick) at the hit: x (side) and y (height) in the stance's root frame.
  /// Kicks: z is measured forward from where the pelvis is at the hit. Punches: z is unused, the
  /// fist lands arm_extension of the arm's length from the shoulder (wherever the body layer has
  /// taken the shoulder), straight ahead of it.
  vec3 target_m{0.0f};
  float arm_extension = 0.95f;
  float duration_s = 0.8f;
  float hit_s = 0.3f;      ///< Full extension at the target (the annotated hit frame).
  // Body layer at the hit (all zero at the start and end of the clip).
  vec3 pelvis_shift_m{0.0f};     ///< Pelvis moves (clip space).
  vec3 pelvis_ypr_rad{0.0f};     ///< Pelvis yaw / pitch (negative leans back) / roll.
  vec3 spine_ypr_rad{0.0f};      ///< Chest relative to pelvis.
  float support_heel_rad = 0.0f; ///< Rolls a foot onto its ball (kicks: the support foot) ...
  float support_pivot_rad = 0.0f;///< ... and pivots it about the ball (positive: turns left).
  int pivot_foot = -1;           ///< Punches: which foot rolls and pivots (-1: none).
  // Punch only.
  vec3 elbow_dir_hit{0, -1, 0};  ///< Clip space.
  std::optional<vec3> hook_via_m;///< The fist sweeps out through here (hooks).
  // Kick only.
  vec3 chamber_m{0.0f};          ///< Ankle with the knee cocked, relative to the kicking hip.
  /// The knee's hinge axis while the foot is in the air (clip space): the knee points along
  /// cross(hip->ankle, knee_axis). +X keeps a front kick's knee in the sagittal plane (up when the
  /// leg is level); +-Y swings a roundhouse's knee in a horizontal plane.
  vec3 knee_axis{1, 0, 0};
  float ankle_point_rad = 0.0f;  ///< Foot relative to the shin at the hit (positive: pointed).
  float toe_bend_hit_rad = 0.0f;
};

/// The stance loop spec (bounce and breathing) and the stance pose itself.
LocomotionSpec fight_stance_spec(const FootGeometry& g);
BodyPose stance_pose(const Skeleton& skeleton, const Rig& rig, const FootGeometry& g);

/// idle -> stance and stance -> idle.
LocomotionSpec idle_to_stance_spec(const FootGeometry& g);
LocomotionSpec stance_to_idle_spec(const FootGeometry& g);

/// The default strikes: per side four punches and four kicks.
std::vector<StrikeSpec> default_strikes();

/// The strike's body at time t.
BodyPose strike_pose(const Skeleton& skeleton, const Rig& rig, const FootGeometry& g,
                     const StrikeSpec& strike, float t_s);
Clip bake_strike(const Skeleton& skeleton, const Rig& rig, const FootGeometry& g,
                 const StrikeSpec& strike);
/// Frame index of the hit.
int strike_hit_frame(const StrikeSpec& strike);
/// The strike's target in clip space (resolving target_m's pelvis-relative z).
vec3 strike_target(const Skeleton& skeleton, const Rig& rig, const FootGeometry& g,
                   const StrikeSpec& strike);

}  // namespace foresight::author

#pragma once
// The gait generator: one function turns a LocomotionSpec (a root path, per-foot timelines, and
// the styles at its two ends) into BodyPoses. Every locomotion, idle, crouch and stance clip of the
// default library is a LocomotionSpec; they differ only in parameters.
//
// Per frame: the style is blended between the start and end families; feet are sampled from their
// timelines (planted feet are pinned in world space); the pelvis follows the root path, sways over
// the loaded foot, twists with the stride, lists, and is kept low enough for both legs to reach
// (soft minimum with the nominal height: this is what makes a walking pelvis dip at double support);
// the chest counter-rotates, the head looks along the path, and the arms swing opposite the legs
// (or hold the guard). Legs and arms are then solved by two-bone IK (solve_body_pose).
#include "anim/author/body_pose.hpp"
#include "anim/author/gait_style.hpp"
#include "anim/author/root_path.hpp"

#include <cstdint>
#include <string>

namespace foresight::author {

/// Secondary motion of a standing loop; every term is a whole number of sine periods over the clip,
/// so it vanishes at both boundaries.
struct StandingMotion {
  float sway_m = 0.0f;        ///< Side-to-side weight shift, one period.
  float breathe_rad = 0.0f;   ///< Chest rise, one period.
  float bounce_m = 0.0f;      ///< Pelvis bounce (fighting stance), `bounce_cycles` periods.
  int bounce_cycles = 2;
};

struct LocomotionSpec {
  std::string name;
  uint32_t tags = 0;
  float duration_s = 1.0f;
  FamilyId start_family = FamilyId::kIdle;
  FamilyId end_family = FamilyId::kIdle;
  float style_blend_begin_s = 0.0f;  ///< The style moves from start to end family over this window.
  float style_blend_end_s = 0.0f;
  RootPath path;
  std::array<FootTimeline, 2> feet;
  StandingMotion standing;

  int num_frames(float fps) const;
};

/// The foot key covering a family boundary at time t_s, for a root frame placed at `root`:
/// a plant (moving families: with the times near the boundary fixed by the family, the far ones at
/// their neutral values for the caller to override) or a via for a foot caught mid-swing.
FootKey boundary_key(const GaitFamily& family, int side, const Placement& root, float t_s,
                     const FootGeometry& geometry);

/// A plant on a path: the ankle at `offset_m` (x: to the left, y: ahead) in the root frame at
/// time anchor_s, the foot yawed by `yaw_rad` relative to it.
FootPlant path_plant(const RootPath& path, float anchor_s, vec2 offset_m, float yaw_rad);

/// Timings of one gait cycle clip as fractions of its duration (interior events only; events near
/// the boundaries follow the families).
struct CycleTiming {
  float left_lift = -1.0f;   ///< < 0: the start family's stance fraction.
  float right_land = 0.5f;
  float right_lift = -1.0f;  ///< Only when the end family runs (a foot mid-air at the end).
};

/// One gait cycle (two steps) from a start-family boundary to an end-family boundary `end` away,
/// with the given speeds at both ends.
LocomotionSpec cycle_spec(const std::string& name, uint32_t tags, FamilyId start, FamilyId end_family,
                          float duration_s, Placement end, float start_speed_mps,
                          float end_speed_mps, const FootGeometry& geometry,
                          CycleTiming timing = {});

/// A standing loop of a standing family (both feet planted throughout).
LocomotionSpec standing_spec(const std::string& name, uint32_t tags, FamilyId family,
                             float duration_s, StandingMotion motion, const FootGeometry& geometry);

/// A clip between two families made of single steps: each foot starts on its start-family key and
/// ends on its end-family key; set_step then says when each foot moves.
LocomotionSpec transition_spec(const std::string& name, uint32_t tags, FamilyId start,
                               FamilyId end_family, float duration_s, Placement end,
                               float start_speed_mps, float end_speed_mps,
                               const FootGeometry& geometry);
/// Times one step of `side` in a transition_spec: the heel roll and lift-off from its first plant
/// (< 0: keep the family's) and the touch-down on its last plant.
void set_step(LocomotionSpec& spec, int side, float heel_off_s, float lift_s, float land_s);

/// The end placement of an arc `length_m` long turning by `turn_rad` (positive: left).
Placement arc_end(float length_m, float turn_rad);

/// The body at time t.
BodyPose gait_pose(const Skeleton& skeleton, const Rig& rig, const LocomotionSpec& spec, float t_s);

/// Bakes the spec at 30 fps.
Clip bake_locomotion(const Skeleton& skeleton, const Rig& rig, const LocomotionSpec& spec);

/// Foot geometry of a rig (heel roll pivot, sole clearance).
FootGeometry foot_geometry(const Rig& rig);

inline constexpr float kFps = 30.0f;

}  // namespace foresight::author

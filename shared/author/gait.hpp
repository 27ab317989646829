#pragma once
// The gait generator: one function turns a LocomotionSpec (a root path, per-foot timelines, and
// the styles at its two ends) into BodyPoses. Every locomotion, idle, crouch and stance clip of the
// default library is a LocomotionSpec; they differ only in parameters.
//
// Per frame: the style is blended between the start and end families; feet are sampled from their
// timelines (planted feet are pinned in world space); the pelvis follows the root path, sways over
// the loaded foot, yaws with the swinging leg (square to the path whenever both balls of the feet
// are still, so at every walking foot strike), lists, and is kept low enough for both legs to
// reach (soft minimum with the nominal height: this is what makes a walking pelvis dip at double
// support); the chest counter-rotates against the legs, the head looks along the path, and the
// arms swing opposite the legs (or hold the guard). Legs and arms are then solved by two-bone IK
// (solve_body_pose). The clip builders are in step_spec.hpp and standing_specs.hpp.
#include "author/body_pose.hpp"
#include "author/gait_style.hpp"
#include "author/root_path.hpp"

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

/// The style at time t (blended from the start family's to the end family's).
GaitStyle style_at(const LocomotionSpec& spec, float t_s);

/// The body at time t.
BodyPose gait_pose(const Skeleton& skeleton, const Rig& rig, const LocomotionSpec& spec, float t_s);

/// Bakes the spec at 30 fps.
Clip bake_locomotion(const Skeleton& skeleton, const Rig& rig, const LocomotionSpec& spec);

/// Foot geometry of a rig (heel roll pivot, sole clearance).
FootGeometry foot_geometry(const Rig& rig);

inline constexpr float kFps = 30.0f;

}  // namespace foresight::author

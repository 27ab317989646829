#pragma once
// Analytic two-bone IK for limbs whose two bones point along -Y at rest (hip-knee-ankle,
// shoulder-elbow-wrist): places the middle joint by the law of cosines, in the plane spanned by the
// root->target line and a bend direction, and returns the upper bone's global rotation and the
// lower joint's local hinge rotation (about its own X axis).
#include "math/types.hpp"

namespace foresight::author {

enum class HingeSide {
  kKnee,   ///< The lower bone folds towards the upper bone's -Z (a knee: the shin swings back).
  kElbow,  ///< The lower bone folds towards +Z (an elbow: the forearm swings forward).
};

struct TwoBoneSolution {
  quat upper_global;   ///< Global rotation of the root joint (orients the upper bone).
  quat lower_local;    ///< Local rotation of the middle joint: a pure rotation about its X axis.
  vec3 mid_m{0.0f};    ///< Where the middle joint lands.
  vec3 end_m{0.0f};    ///< Where the end joint lands (the target unless out of reach).
  bool reached = true; ///< False when the target was beyond the soft reach limit.
};

/// Fraction of full extension where reach starts being softened (targets closer are met exactly).
inline constexpr float kIkSoftReachStart = 0.995f;

/// root_m: the root joint's position; target_m: where the end joint should go; bend_dir: where the
/// middle joint should point (only its part perpendicular to root->target matters). Targets beyond
/// kIkSoftReachStart of full extension are approached smoothly, never fully straightening the limb.
TwoBoneSolution solve_two_bone(vec3 root_m, vec3 target_m, float upper_m, float lower_m,
                               vec3 bend_dir, HingeSide hinge);

}  // namespace foresight::author

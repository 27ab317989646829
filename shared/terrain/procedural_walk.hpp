#pragma once
// The procedural walk of the decoupled footstep paper (4.1), in the sagittal plane: x = distance
// along the ground profile, y = up, metres and radians.
//
// One step: the swing foot leaves the rear foothold, passes the stance foot and lands on the next
// foothold. Three key frames (Fig. 4) define it: K0 double support at lift-off, K1 passing (pelvis
// over the stance foot), K2 double support at landing. The category comes from the height change
// stance -> landing: level, uphill (the front leg bends first: the pelvis stays low at landing and
// rises over the next step) or downhill (the rear leg bends first: the stance knee flexes in the
// passing frame and lowers the pelvis before the front foot lands). Between key frames the stance
// leg's joint angles are interpolated (the stance foot stays planted, the pelvis follows by forward
// kinematics); the swing ankle follows a cubic Bezier whose two inner control points are raised
// just enough for the foot to clear the ground profile (the paper's Bezier adjustment, solved in
// one pass: the curve's height is linear in the control points' height).
//
// Joint angles (LegPose): hip = thigh angle from straight down, positive forward (flexion);
// knee = flexion >= 0; ankle = dorsiflexion (toes toward the shin) positive.
#include "terrain/ground_profile.hpp"

#include <array>
#include <cstdint>

namespace foresight::terrain {

/// The leg and foot geometry, from the default skeleton (anim/author/default_skeleton.cpp) unless
/// said otherwise, and the walk's tuning.
struct WalkParams {
  float thigh_m = 0.42f;             ///< Hip joint to knee.
  float shin_m = 0.42f;              ///< Knee to ankle.
  float hip_below_pelvis_m = 0.05f;  ///< Hip joints below the pelvis (Hips) joint.
  float ankle_height_m = 0.08f;      ///< Ankle above the sole.
  float toe_front_m = 0.19f;         ///< Toe tip ahead of the ankle (ball 0.13 + toe 0.06).
  float heel_back_m = 0.06f;         ///< Heel behind the ankle (the skeleton has no heel joint).
  float pelvis_height_m = 0.95f;     ///< Walking pelvis height above the stance sole (rest 0.97).
  /// Double support keeps both legs at most this fraction of their length: the pelvis drops on
  /// long strides, which leaves the swing leg reach to spare while the joint-interpolated pelvis
  /// lags behind the straight line near the ends of the step.
  float double_support_leg_fraction = 0.97f;
  float level_threshold_m = 0.04f;   ///< |height change| up to this is a level step.
  float max_step_up_m = 0.40f;       ///< Higher is a wall for the footstep planner.
  float max_step_down_m = 0.45f;     ///< Lower is a cliff.
  float foot_max_pitch_rad = 0.35f;  ///< Steepest ground a foot may stand on (20 degrees).
  float foot_max_gap_m = 0.03f;      ///< Largest dip under a planted sole (straddling an edge).
  float swing_clearance_m = 0.04f;   ///< Swing sole above the ground in mid-swing.
  float swing_min_lift_m = 0.05f;    ///< Control points at least this above the higher end.
  float swing_max_lift_m = 0.60f;    ///< Control points at most this above the higher end.
  float max_knee_rad = 2.4f;         ///< Deepest knee flexion (137 degrees).
  int swing_samples = 12;            ///< Curve samples checked against the profile. [2, 64]
};

/// The default skeleton's legs (reads anim/author/default_skeleton; allocates, call once).
WalkParams walk_params_from_default_skeleton();

enum class StepKind : std::uint8_t { kLevel, kUphill, kDownhill };
const char* step_kind_name(StepKind kind);

/// Why a step (or a foothold) is impossible; kOk when it is fine.
enum class WalkStatus : std::uint8_t {
  kOk,
  kOutsideProfile,  ///< A foot (or the swing path) leaves the profile: no ground data there.
  kFootInGap,       ///< No ground under part of the foot.
  kFootholdUneven,  ///< The sole would straddle an edge or stand on too steep a slope.
  kStepTooHigh,     ///< Landing higher than max_step_up_m: a wall.
  kStepTooLow,      ///< Landing lower than max_step_down_m: a cliff.
  kNoClearance,     ///< No Bezier lift within swing_max_lift_m clears the ground.
  kUnreachable,     ///< A key frame or the swing ankle is out of the leg's reach.
};
const char* walk_status_name(WalkStatus status);

/// Where a planted foot rests: ankle at x_m, sole at the ankle sole_y_m, sole pitched by pitch_rad
/// (positive = toes up), lying on the ground profile.
struct Foothold {
  float x_m = 0.0f;
  float sole_y_m = 0.0f;
  float pitch_rad = 0.0f;
};

/// Fits the sole to the profile under a foot whose ankle is at x_m: the sole line through the
/// ground at heel and toe, raised until no ground is above it. kOk, kOutsideProfile, kFootInGap,
/// or kFootholdUneven (pitch above the limit, or a dip deeper than foot_max_gap_m under it).
WalkStatus foothold_fit(const GroundProfile& profile, const WalkParams& params, float x_m,
                        Foothold& out);

struct LegPose {
  float hip_rad = 0.0f;
  float knee_rad = 0.0f;
  float ankle_rad = 0.0f;
};

struct WalkKeyFrame {
  float phase = 0.0f;  ///< In [0, 1] over the step.
  vec2 pelvis_m{0.0f};
  LegPose stance;
  LegPose swing;
};

/// One planned step, ready to sample. Fixed size; no allocation.
struct WalkStep {
  StepKind kind = StepKind::kLevel;
  Foothold rear, stance, land;          ///< Swing from rear to land over stance.
  std::array<WalkKeyFrame, 3> keys;     ///< K0 (lift-off), K1 (passing), K2 (landing).
  std::array<vec2, 4> swing_ankle_bezier_m{};  ///< Cubic Bezier of the swing ankle.
  float lift_m = 0.0f;  ///< Height of the inner control points above the higher end ankle.
  /// Curve parameter where the swing ankle passes the stance ankle: reached at phase 0.5 (K1).
  float swing_param_at_passing = 0.5f;
};

/// Plans one step: category, key frames, swing curve adjusted to clear the profile, reach checks.
/// The footholds must come from foothold_fit (kOk). Returns kOk, kStepTooHigh, kStepTooLow,
/// kNoClearance, kUnreachable or kOutsideProfile; `out` is complete only on kOk. No allocation.
WalkStatus walk_step_plan(const GroundProfile& profile, const WalkParams& params,
                          const Foothold& rear, const Foothold& stance, const Foothold& land,
                          WalkStep& out);

/// A sampled instant of a step.
struct WalkFrame {
  vec2 pelvis_m{0.0f};
  LegPose stance, swing;
  vec2 stance_knee_m{0.0f}, swing_knee_m{0.0f};
  vec2 stance_ankle_m{0.0f}, swing_ankle_m{0.0f};
  float swing_foot_pitch_rad = 0.0f;
  vec2 swing_heel_m{0.0f}, swing_toe_m{0.0f};  ///< Sole ends of the swing foot.
};

/// Samples a planned step at phase in [0, 1] (clamped): stance joints interpolated between the key
/// frames, pelvis by forward kinematics from the planted stance ankle, swing ankle on the curve and
/// its joints by two-bone IK.
void walk_step_sample(const WalkStep& step, const WalkParams& params, float phase, WalkFrame& out);

}  // namespace foresight::terrain

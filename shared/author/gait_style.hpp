#pragma once
// Gait styles and families. A style is the set of numbers that turns feet into a whole body (pelvis
// height, sway, twist, lean, arm swing, swing-foot shape). A family is a style plus its boundary
// convention: the one pose every clip of the family starts and ends in, relative to the root
// placement. Clips that end in family F and clips that start in F can follow each other.
#include "author/footsteps.hpp"

#include <array>
#include <string_view>

namespace foresight::author {

/// Reference speed of GaitStyle::twist_rad.
inline constexpr float kTwistSpeedMps = 5.0f;

struct GaitStyle {
  float pelvis_height_m = 0.955f;   ///< Nominal pelvis height (legs permitting).
  float pelvis_back_m = 0.0f;       ///< Pelvis behind the root (balances a forward-bent trunk).
  float pelvis_pitch_rad = 0.05f;   ///< Forward tilt.
  float stance_dip_m = 0.0f;        ///< Pelvis drop with a loaded foot under the hip (running).
  float reach_fraction = 0.993f;    ///< Max hip-ankle distance over leg length (IK is exact below 0.995).
  float sway_gain = 0.5f;           ///< Fraction of the loaded foot's side offset the pelvis follows.
  /// Pelvis yaw with one ball of the foot moving forward at kTwistSpeedMps and the other still:
  /// the hip of a swinging leg comes forward with it (yaw grows with the square of the speed, so
  /// it sets in and dies out smoothly), and the pelvis is square at every walking foot strike.
  float twist_rad = 0.08f;
  float list_rad = 0.05f;           ///< Pelvis roll up on the loaded side.
  float spine_pitch_rad = 0.03f;    ///< Chest bend forward relative to the pelvis.
  float spine_yaw_rad = 0.0f;       ///< Static chest turn (fighting stance blades the shoulders).
  /// Chest yaw (relative to the root) per metre the left foot leads the right: the shoulders
  /// turn against the legs, in phase with the arm swing.
  float chest_counter_rad_per_m = 0.096f;
  float head_pitch_rad = 0.08f;     ///< Gaze below the horizon.
  float arm_swing_rad_per_m = 0.5f; ///< Shoulder swing per metre the opposite foot leads.
  float arm_flex_rad = 0.05f;       ///< Arms held this far forward.
  float arm_abduction_rad = 0.12f;  ///< Arms held this far out.
  float elbow_rad = 0.25f;          ///< Elbow bend.
  float elbow_swing_rad_per_rad = 0.5f;  ///< Extra elbow bend per radian of forward swing.
  float guard = 0.0f;               ///< 0: hanging, swinging arms. 1: fighting guard.
  float clavicle_raise_rad = 0.0f;
  float lift_pitch_rad = 0.6f;      ///< Heel-up pitch of a foot at lift-off.
  float weight_accept_s = 0.2f;     ///< Time for the weight to come onto a foot after touch-down.
  SwingShape swing;
};

GaitStyle mix(const GaitStyle& a, const GaitStyle& b, float w);

/// Boundary families. Every gait comes as a mirror pair: ..L boundaries are left-foot strikes,
/// ..R boundaries right-foot strikes, and every step clip goes from one to the other.
enum class FamilyId {
  kIdle,
  kWalkL, kWalkR,
  kSlowL, kSlowR,
  kRunL, kRunR,
  kCrouchIdle,
  kCrouchWalkL, kCrouchWalkR,
  kFight,
};
inline constexpr int kNumFamilies = 11;

/// Boundary convention of a moving family (see docs/DEFAULT_LIBRARY.md): at the boundary the lead
/// foot has just touched down, flat, `stance_fraction * stride / 2 + foot_forward` ahead of the
/// root; the other foot is either still planted behind (stance_fraction > 0.5: double support)
/// or in the air mid-swing (running). A standing family has both feet planted at fixed spots.
struct GaitFamily {
  FamilyId id = FamilyId::kIdle;
  std::string_view name;
  GaitStyle style;
  bool moving = false;
  // Moving families.
  int lead_side = 0;             ///< The foot that has just struck at a boundary (kLeft/kRight).
  float cycle_s = 1.0f;          ///< Nominal gait cycle (two steps).
  float stride_m = 1.0f;         ///< Distance covered per cycle at the boundary pace.
  float stance_fraction = 0.6f;  ///< Part of the cycle a foot is on the floor.
  float heel_off_fraction = 0.25f;  ///< Part of the cycle the heel roll lasts before lift-off.
  float step_width_m = 0.055f;   ///< Ankle's side offset from the root line.
  float foot_forward_m = 0.0f;   ///< Footprint ahead of the root at mid-stance.
  float toe_out_rad = 0.08f;
  // Standing families: ankle positions (root frame) and foot yaws, left then right.
  std::array<vec2, 2> stand_ankle_m{vec2(0.11f, 0.0f), vec2(-0.11f, 0.0f)};
  std::array<float, 2> stand_yaw_rad{0.12f, -0.12f};

  float speed_mps() const { return moving ? stride_m / cycle_s : 0.0f; }
};

const GaitFamily& gait_family(FamilyId id);

/// The moving family of the same gait whose boundary is a strike of `lead_side`; standing
/// families map to themselves.
FamilyId strike_family(FamilyId gait, int lead_side);

/// Guard hand placement (chest axes, relative to the shoulder joint) for a side.
vec3 guard_wrist_m(int side);
vec3 guard_elbow_dir(int side);

}  // namespace foresight::author

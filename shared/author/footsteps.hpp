#pragma once
// Foot timelines: per foot, a time-sorted list of plants (the foot pinned on the floor, optionally
// rolling onto the ball of the foot before lift-off, and pivoting about the ball while the heel is
// up) and vias (a swing caught mid-air at a clip
// boundary). Between two keys the foot swings on a smooth lifted curve. Sampling is pure, so a
// planted foot is exactly still in world space whatever the pelvis does.
#include "math/types.hpp"

#include <functional>
#include <vector>

namespace foresight::author {

inline constexpr float kOpenPastS = -1.0e3f;   ///< Land time of a foot planted "forever".
inline constexpr float kOpenFutureS = 1.0e3f;  ///< Lift time of a foot that never lifts.

/// Flat-foot geometry used for the heel roll and for keeping the sole above the floor.
struct FootGeometry {
  float ankle_height_m = 0.08f;
  vec3 ball_from_ankle_m{0, -0.055f, 0.13f};  ///< Ball of the foot (ToeBase), foot frame.
  vec3 toe_from_ball_m{0, 0, 0.06f};          ///< Toe tip, toe frame.
  float sole_below_ball_m = 0.025f;
  vec3 heel_from_ankle_m{0, -0.08f, -0.05f};  ///< Back of the heel on the sole, foot frame.
};

struct FootPlant {
  vec2 ankle_xz_m{0.0f};      ///< Ankle over the ground with the foot flat.
  float yaw_rad = 0.0f;       ///< Foot heading (toes along forward(yaw)).
  float land_s = kOpenPastS;  ///< Touch-down time.
  float heel_off_s = kOpenFutureS;  ///< The heel starts rising (rolling about the ball).
  float lift_s = kOpenFutureS;      ///< The ball leaves the floor.
  float lift_pitch_rad = 0.5f;      ///< Heel-up pitch reached at lift-off.
  /// Yaw the foot turns about the ball of the foot while the heel is up: eased in from heel_off_s,
  /// complete at pivot_end_s (a turning step ends with its rear foot pivoted to the new heading).
  float pivot_rad = 0.0f;
  float pivot_end_s = kOpenFutureS;

  /// The foot's yaw at time t (the pivot applied).
  float yaw_at(float t_s) const;
  /// The ball of the foot on the floor (fixed while the foot is planted).
  vec2 ball_xz(const FootGeometry& g) const;
};

/// A swing passing through a fixed state at `time_s` (a clip boundary caught mid-swing). `u` is the
/// swing's progress there; base_ankle_m is the ankle without the swing's lift bump.
struct FootVia {
  float time_s = 0.0f;
  float u = 0.5f;
  vec3 base_ankle_m{0.0f};
  float yaw_rad = 0.0f;
  float lift_pitch_rad = 0.5f;  ///< Pitch the swing started with (shapes the rest of it).
};

struct FootKey {
  bool is_via = false;
  FootPlant plant;
  FootVia via;
  float start_s() const { return is_via ? via.time_s : plant.land_s; }
  float end_s() const { return is_via ? via.time_s : plant.lift_s; }
};
using FootTimeline = std::vector<FootKey>;

inline FootKey plant_key(const FootPlant& p) { return {false, p, {}}; }
inline FootKey via_key(const FootVia& v) { return {true, {}, v}; }

/// Swing shape at a moment (from the gait style there).
struct SwingShape {
  float height_m = 0.06f;      ///< Extra ankle lift at the top of the swing.
  float ease_exponent = 1.0f;  ///< > 1 keeps the foot back longer (running heel recovery).
  float toe_up_rad = 0.15f;    ///< Toe lift in the second half of the swing.
  float bow_m = 0.02f;         ///< Outward bulge of the swing path (clears the other ankle).
};

struct FootSample {
  vec3 ankle_m{0.0f};
  float yaw_rad = 0.0f;
  float pitch_rad = 0.0f;     ///< Positive: heel up.
  float toe_bend_rad = 0.0f;  ///< ToeBase relative to the foot; negative: toes up.
  float load = 0.0f;          ///< 0..1, how much the foot carries: a bell over the stance.
  bool planted = false;
};

/// Horizontal progress of a swing at phase u (0 lift-off, 1 touch-down).
float swing_progress(float u, float ease_exponent);
/// Vertical lift profile of a swing (0 at both ends, 1 at the top, which comes early).
float swing_bump(float u);

/// Ankle position while the foot rolls about the ball by `pitch_rad` (heel up) from a flat plant
/// whose ankle is at ankle_xz_m with yaw flat_yaw_rad, having pivoted about the ball to yaw_rad.
vec3 rolled_ankle(const FootGeometry& g, vec2 ankle_xz_m, float flat_yaw_rad, float yaw_rad,
                  float pitch_rad);

/// Where the character's root frame is at a time.
using PlacementAt = std::function<Placement(float)>;

/// Samples one foot at time t. outward_sign: +1 for the left foot, -1 for the right (the swing
/// bows outwards). load_in_s: how long the weight takes to come onto a foot after touch-down
/// (the weight leaves over the heel roll). `shape_at` gives the swing shape at a time (evaluated
/// at t for the lift, at the segment's middle for the ease, so each segment is monotone).
/// `root_at`: the root frame; where it turns during a swing, the swing follows an arc bulging to
/// the outside instead of the straight chord (the outside foot of a turn does not cut across the
/// planted one), and the foot's yaw turns with the root.
FootSample sample_foot(const FootTimeline& keys, float t_s, const FootGeometry& g, float outward_sign,
                       float load_in_s, const std::function<SwingShape(float)>& shape_at,
                       const PlacementAt& root_at);

/// Lowest sole point (heel, ball, toe tip) above the floor for a foot at `ankle_m` (negative: below).
float sole_clearance(const FootGeometry& g, vec3 ankle_m, float yaw_rad, float pitch_rad,
                     float toe_bend_rad);

/// The base state a neutral swing from `lift` to `land` has at phase u: used to build vias.
FootVia via_between(const FootPlant& lift, const FootPlant& land, float time_s, float u,
                    const FootGeometry& g, float ease_exponent);

}  // namespace foresight::author

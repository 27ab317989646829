#pragma once
// The ground profile (decoupled footstep paper, 4.2): the terrain cut by the actor's sagittal plane
// along the walking path, as heights sampled at a fixed spacing of arc length. The footstep
// planner and the procedural walk only ever see this 2D cut (x = distance along the path, y = up).
//
// Sampling: sample i stands for the half-open cell [i * spacing, (i + 1) * spacing) of the path
// and holds the ground height there; NaN means no ground (a gap, or beyond the world). The profile
// has a fixed capacity, so building one never allocates.
#include "math/types.hpp"
#include "world/scene.hpp"

#include <array>
#include <cstdint>

namespace foresight::terrain {

inline constexpr int kMaxProfileSamples = 1024;
inline constexpr float kDefaultProfileSpacing_m = 0.02f;

inline constexpr int kMaxPathPieces = 6;

/// The walking path on the ground plane: a straight line (curvature 0) or a circular arc, from
/// the user's direction or the paper's drag input (translational v, rotational omega). A steered
/// walk (ground_path_steer) first runs a few pieces of their own curvature, then continues with
/// curvature_per_m.
struct GroundPath {
  struct Piece {
    float length_m = 0.0f;
    float curvature_per_m = 0.0f;
  };
  vec2 start_m{0.0f};
  float heading_rad = 0.0f;      ///< Direction at the start (math/types.hpp: 0 faces +Z).
  float curvature_per_m = 0.0f;  ///< d(heading)/d(arc length) after the pieces; positive turns toward +heading.
  std::array<Piece, kMaxPathPieces> pieces{};
  int num_pieces = 0;
};

/// The path a drag input gives: curvature = omega / v. A (near) zero v gives a straight path
/// (an actor does not walk in place; the caller stops it instead).
GroundPath ground_path_from_velocity(vec2 start_m, float heading_rad, float speed_mps,
                                     float turn_rate_radps);
/// Point at arc length s_m along the path (exact for lines and arcs).
vec2 ground_path_point(const GroundPath& path, float s_m);
/// Heading at arc length s_m.
float ground_path_heading(const GroundPath& path, float s_m);
/// The path of a steered walk's next window, in which nothing already walked moves: `lead_m` of
/// straight line up to the point at `from_s_m` of `walked` (the rear foot), `walked` itself up to
/// `to_s_m` (the stance foot), then a turn by `turn_rad` spread over `turn_length_m`, then straight.
/// The rear foot lands at lead_m, the stance foot at lead_m + (to_s_m - from_s_m).
GroundPath ground_path_steer(const GroundPath& walked, float from_s_m, float to_s_m, float lead_m, float turn_rad,
                             float turn_length_m);

struct GroundProfile {
  float spacing_m = kDefaultProfileSpacing_m;  ///< Arc length per sample. [Limit: > 0]
  int num_samples = 0;                         ///< [0, kMaxProfileSamples]
  std::array<float, kMaxProfileSamples> height_m{};  ///< NaN = no ground.
  GroundPath path;  ///< Where the cut was taken (synthetic profiles: the origin, heading 0).

  float length_m() const { return static_cast<float>(num_samples) * spacing_m; }
  /// Sample index of the cell containing s_m, or -1 outside [0, length). NaN gives -1.
  int index_at(float s_m) const {
    const float f = s_m / spacing_m;
    if (!(f >= 0.0f && f < static_cast<float>(num_samples))) return -1;
    return static_cast<int>(f);
  }
  /// Ground at s_m: false over a gap or outside the profile.
  bool height_at(float s_m, float& h_m) const;
};

/// How a scene is cut.
struct ProfileCutOptions {
  float spacing_m = kDefaultProfileSpacing_m;
  /// The feet walk on two lines beside the path (hip width plus half a foot): the cut takes the
  /// highest ground over {-w, 0, +w} sideways, and a hole under any of them is a gap. 0 = the
  /// centre line only, as in the paper.
  float lateral_half_width_m = 0.14f;
  /// Boxes whose bottom is at most this far above the ground are obstacles for the legs and show
  /// in the profile as raised ground up to their top (a wall becomes a vertical wall, a crate a
  /// block too high to climb). Higher boxes (lintels, shelves, tables) are the upper body's.
  float leg_obstacle_max_bottom_m = 0.5f;
};

/// Cuts the scene along `path` for `length_m` (capped at capacity): terrain (floor, height field
/// with holes, steps), leg-height boxes, and NaN outside the scene bounds. Returns false (profile
/// empty) on a non-positive/NaN length or spacing. Cost: O(samples * (steps + boxes)); not a hot
/// loop (once per planned step, on a few metres).
bool ground_profile_from_scene(const Scene& scene, const GroundPath& path, float length_m,
                               const ProfileCutOptions& options, GroundProfile& out);

// Synthetic profiles for tests and seeded benchmarks (distances along the profile).

/// A flat profile of `length_m` at height_m (capped at capacity).
void ground_profile_flat(GroundProfile& out, float length_m, float height_m,
                         float spacing_m = kDefaultProfileSpacing_m);
/// Sets the cells whose centres lie in [from_m, to_m) to height_m (NaN makes a gap).
void ground_profile_fill(GroundProfile& profile, float from_m, float to_m, float height_m);
/// A straight ramp over [from_m, to_m) from h0 to h1; the ground beyond keeps h1.
void ground_profile_ramp(GroundProfile& profile, float from_m, float to_m, float h0_m, float h1_m);
/// A seeded random profile: flat, then a mix of blocks (up/down 0.05-0.3 m), gaps (0.1-0.6 m),
/// slopes (gradient <= 0.25) and bumps, spaced so that a walker can in principle pass them.
/// Deterministic for a seed.
void ground_profile_random(GroundProfile& out, std::uint64_t seed, float length_m,
                           float spacing_m = kDefaultProfileSpacing_m);

}  // namespace foresight::terrain

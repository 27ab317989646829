#include "terrain/ground_profile.hpp"

#include "math/splitmix64.hpp"

#include "world/terrain.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace foresight::terrain {

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

int capped_samples(float length_m, float spacing_m) {
  if (!(length_m > 0.0f) || !(spacing_m > 0.0f)) return 0;
  const float n = std::ceil(length_m / spacing_m);
  return n >= static_cast<float>(kMaxProfileSamples) ? kMaxProfileSamples : static_cast<int>(n);
}

// Ground at one point of the scene: terrain, raised by leg-height boxes, NaN outside the bounds.
float scene_ground_at(const Scene& scene, vec2 p, float leg_obstacle_max_bottom_m) {
  if (!scene.bounds.contains(p)) return kNaN;
  float h = 0.0f;
  bool has_ground = terrain_height_at(scene.terrain, p, h);
  for (const SceneBox& box : scene.boxes) {
    if (!box.ground_rect().contains(p)) continue;
    // Over a hole there is no reference height: a box standing in a hole still blocks the legs.
    const float base = has_ground ? h : box.min_m.y;
    if (box.min_m.y > base + leg_obstacle_max_bottom_m) continue;
    h = has_ground ? std::max(h, box.max_m.y) : box.max_m.y;
    has_ground = true;
  }
  return has_ground ? h : kNaN;
}


}  // namespace

GroundPath ground_path_from_velocity(vec2 start_m, float heading_rad, float speed_mps,
                                     float turn_rate_radps) {
  GroundPath path{start_m, heading_rad, 0.0f};
  if (std::abs(speed_mps) > 1e-3f && std::isfinite(turn_rate_radps))
    path.curvature_per_m = turn_rate_radps / speed_mps;
  return path;
}

namespace {

// Point at s_m along one arc (or line) from p facing h.
vec2 arc_point(vec2 p, float h, float k, float s_m) {
  if (std::abs(k) < 1e-6f) return p + vec2(std::sin(h), std::cos(h)) * s_m;
  // Arc: heading(s) = h + k s; integrate forward(heading) = (sin, cos).
  const float h1 = h + k * s_m;
  return p + vec2(std::cos(h) - std::cos(h1), std::sin(h1) - std::sin(h)) / k;
}

// Walks the pieces up to s_m: the point and heading where the piece holding s_m starts, its
// curvature and the distance left into it (before the start: the first piece, extended back).
struct PathCursor {
  vec2 p;
  float h, k, s;
};
PathCursor path_cursor(const GroundPath& path, float s_m) {
  PathCursor c{path.start_m, path.heading_rad, path.curvature_per_m, s_m};
  for (int i = 0; i < path.num_pieces; ++i) {
    const GroundPath::Piece& piece = path.pieces[static_cast<size_t>(i)];
    if (c.s <= piece.length_m) return {c.p, c.h, piece.curvature_per_m, c.s};
    c.p = arc_point(c.p, c.h, piece.curvature_per_m, piece.length_m);
    c.h += piece.curvature_per_m * piece.length_m;
    c.s -= piece.length_m;
  }
  return c;
}

void add_piece(GroundPath& path, float length_m, float curvature_per_m) {
  if (!(length_m > 0.0f)) return;
  // ground_path_steer makes at most 4 pieces (lead-in, two of the walked stretch, the turn); a
  // caller going beyond the capacity gets the rest merged into the last piece.
  if (path.num_pieces == kMaxPathPieces) {
    path.pieces[static_cast<size_t>(path.num_pieces - 1)].length_m += length_m;
    return;
  }
  path.pieces[static_cast<size_t>(path.num_pieces++)] = {length_m, curvature_per_m};
}

}  // namespace

vec2 ground_path_point(const GroundPath& path, float s_m) {
  const PathCursor c = path_cursor(path, s_m);
  return arc_point(c.p, c.h, c.k, c.s);
}

float ground_path_heading(const GroundPath& path, float s_m) {
  const PathCursor c = path_cursor(path, s_m);
  return wrap_angle(c.h + c.k * c.s);
}

GroundPath ground_path_steer(const GroundPath& walked, float from_s_m, float to_s_m, float lead_m, float turn_rad,
                             float turn_length_m) {
  const float h0 = ground_path_heading(walked, from_s_m);
  GroundPath out;
  out.start_m = ground_path_point(walked, from_s_m) - lead_m * vec2(std::sin(h0), std::cos(h0));
  out.heading_rad = h0;
  add_piece(out, lead_m, 0.0f);
  // The walked stretch, piece by piece (the tail beyond the pieces is one more).
  float s = 0.0f;
  for (int i = 0; i <= walked.num_pieces && s < to_s_m; ++i) {
    const bool tail = i == walked.num_pieces;
    const float len = tail ? to_s_m - s : walked.pieces[static_cast<size_t>(i)].length_m;
    const float k = tail ? walked.curvature_per_m : walked.pieces[static_cast<size_t>(i)].curvature_per_m;
    const float a = std::max(s, from_s_m), b = std::min(s + len, to_s_m);
    add_piece(out, b - a, k);
    s += len;
  }
  if (turn_length_m > 0.0f) add_piece(out, turn_length_m, turn_rad / turn_length_m);
  out.curvature_per_m = 0.0f;
  return out;
}

bool GroundProfile::height_at(float s_m, float& h_m) const {
  const int i = index_at(s_m);
  if (i < 0 || std::isnan(height_m[static_cast<std::size_t>(i)])) return false;
  h_m = height_m[static_cast<std::size_t>(i)];
  return true;
}

bool ground_profile_from_scene(const Scene& scene, const GroundPath& path, float length_m,
                               const ProfileCutOptions& options, GroundProfile& out) {
  out.num_samples = 0;
  out.spacing_m = options.spacing_m > 0.0f ? options.spacing_m : kDefaultProfileSpacing_m;
  out.path = path;
  const int n = capped_samples(length_m, options.spacing_m);
  if (n == 0) return false;
  const float w = std::max(0.0f, options.lateral_half_width_m);
  const int num_lines = w > 0.0f ? 3 : 1;
  for (int i = 0; i < n; ++i) {
    const float s = (static_cast<float>(i) + 0.5f) * out.spacing_m;
    const vec2 centre = ground_path_point(path, s);
    const float heading = ground_path_heading(path, s);
    // The character's left is +X at heading 0: left = (cos h, -sin h).
    const vec2 left{std::cos(heading), -std::sin(heading)};
    float h = -std::numeric_limits<float>::infinity();
    for (int line = 0; line < num_lines; ++line) {
      const float offset = line == 0 ? 0.0f : (line == 1 ? w : -w);
      const float g = scene_ground_at(scene, centre + left * offset,
                                      options.leg_obstacle_max_bottom_m);
      if (std::isnan(g)) {
        h = kNaN;  // A hole under either foot line is a gap for both.
        break;
      }
      h = std::max(h, g);
    }
    out.height_m[static_cast<std::size_t>(i)] = h;
  }
  out.num_samples = n;
  return true;
}

void ground_profile_flat(GroundProfile& out, float length_m, float height_m, float spacing_m) {
  out.spacing_m = spacing_m > 0.0f ? spacing_m : kDefaultProfileSpacing_m;
  out.num_samples = capped_samples(length_m, out.spacing_m);
  out.path = GroundPath{};
  for (int i = 0; i < out.num_samples; ++i) out.height_m[static_cast<std::size_t>(i)] = height_m;
}

void ground_profile_fill(GroundProfile& profile, float from_m, float to_m, float height_m) {
  for (int i = 0; i < profile.num_samples; ++i) {
    const float s = (static_cast<float>(i) + 0.5f) * profile.spacing_m;
    if (s >= from_m && s < to_m) profile.height_m[static_cast<std::size_t>(i)] = height_m;
  }
}

void ground_profile_ramp(GroundProfile& profile, float from_m, float to_m, float h0_m, float h1_m) {
  const float span = std::max(to_m - from_m, 1e-6f);
  for (int i = 0; i < profile.num_samples; ++i) {
    const float s = (static_cast<float>(i) + 0.5f) * profile.spacing_m;
    if (s < from_m) continue;
    const float t = std::min(1.0f, (s - from_m) / span);
    profile.height_m[static_cast<std::size_t>(i)] = h0_m + (h1_m - h0_m) * t;
  }
}

void ground_profile_random(GroundProfile& out, std::uint64_t seed, float length_m,
                           float spacing_m) {
  ground_profile_flat(out, length_m, 0.0f, spacing_m);
  SplitMix64 rng{seed * 0x2545F4914F6CDD1Dull + 1};
  float h = 0.0f;
  // The first 1.5 m stay flat: the walker starts there.
  float s = 1.5f;
  while (s < out.length_m()) {
    const int kind = static_cast<int>(rng.next() % 5);
    const float run = rng.uniform(0.8f, 2.0f);  // Level ground after each feature.
    switch (kind) {
      case 0: {  // A block up or down (a stair step, a curb).
        h += rng.uniform(0.05f, 0.30f) * ((rng.next() & 1) ? 1.0f : -1.0f);
        ground_profile_fill(out, s, out.length_m() + 1.0f, h);
        break;
      }
      case 1: {  // A gap to stride over.
        const float w = rng.uniform(0.10f, 0.60f);
        ground_profile_fill(out, s, s + w, kNaN);
        s += w;
        break;
      }
      case 2: {  // A slope.
        const float len = rng.uniform(0.8f, 2.5f);
        const float dh = len * rng.uniform(-0.25f, 0.25f);
        ground_profile_ramp(out, s, s + len, h, h + dh);
        h += dh;
        s += len;
        break;
      }
      case 3: {  // A low bump or obstacle to step over (a log, a kerb stone).
        const float w = rng.uniform(0.05f, 0.25f);
        ground_profile_fill(out, s, s + w, h + rng.uniform(0.03f, 0.25f));
        s += w;
        break;
      }
      default: break;  // Plain ground.
    }
    s += run;
  }
}

}  // namespace foresight::terrain

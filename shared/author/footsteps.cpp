#include "author/footsteps.hpp"

#include "author/easing.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace foresight::author {
namespace {

// Shortest unloading ramp before a lift-off without a heel roll.
constexpr float kLoadOutS = 0.12f;

// Heel-roll profile: starts with a finite rate (the heel leaves the floor decisively rather than
// creeping: from the first frame of the roll the ankle is visibly rising about the pinned ball)
// and reaches 1 at lift-off.
float heel_roll(float q) {
  q = clamp01(q);
  return q * (0.5f + 0.5f * q);
}

quat foot_rot(float yaw, float pitch) { return quat_ypr(yaw, pitch, 0.0f); }

float swing_pitch(float u, float lift_pitch, float toe_up) {
  const float roll_off = lift_pitch * (1.0f - smoothstep01(u / 0.5f));
  const float x = clamp01((u - 0.3f) / 0.55f);
  const float s = std::sin(kPi * x);
  return roll_off - toe_up * s * s;
}

float swing_toe_bend(float u, float lift_pitch) {
  return -lift_pitch * (1.0f - smoothstep01(u / 0.3f));
}

struct SegmentEnd {
  vec3 base{0.0f};
  float yaw = 0.0f;
  float u = 0.0f;
  float time = 0.0f;
  float lift_pitch = 0.0f;
};

SegmentEnd lift_state(const FootPlant& p, const FootGeometry& g) {
  const float yaw = p.yaw_at(p.lift_s);
  return {rolled_ankle(g, p.ankle_xz_m, p.yaw_rad, yaw, p.lift_pitch_rad), yaw, 0.0f, p.lift_s,
          p.lift_pitch_rad};
}
SegmentEnd land_state(const FootPlant& p, const FootGeometry& g) {
  return {from_ground(p.ankle_xz_m, g.ankle_height_m), p.yaw_rad, 1.0f, p.land_s, 0.0f};
}
SegmentEnd via_state(const FootVia& v) {
  return {v.base_ankle_m, v.yaw_rad, v.u, v.time_s, v.lift_pitch_rad};
}

float load_of(const FootPlant& p, float t, float load_in_s) {
  // A bell over the stance: weight comes on over load_in_s after touch-down and leaves over the
  // whole heel roll (at least kLoadOutS), so a standing foot about to step is unloaded first and
  // the pelvis shifts over the other foot before the step. Each ramp depends on one event time
  // only, so a load near a clip boundary depends only on the boundary's own events.
  const float out = std::max(kLoadOutS, p.lift_s - p.heel_off_s);
  return ramp(t - p.land_s, 0.0f, load_in_s) * ramp(p.lift_s - t, 0.0f, out);
}

}  // namespace

float FootPlant::yaw_at(float t) const {
  if (pivot_rad == 0.0f || t <= heel_off_s) return yaw_rad;
  // Eased in and out: the pivot starts as the heel leaves the floor and is complete (turning no
  // more) at the boundary it leads to.
  const float span = std::max(pivot_end_s - heel_off_s, 1e-4f);
  return yaw_rad + pivot_rad * smoothstep01((t - heel_off_s) / span);
}

vec2 FootPlant::ball_xz(const FootGeometry& g) const {
  return ankle_xz_m + rotate_ground(ground(g.ball_from_ankle_m), yaw_rad);
}

float sole_clearance(const FootGeometry& g, vec3 ankle, float yaw, float pitch, float toe_bend) {
  const quat q = foot_rot(yaw, pitch);
  const vec3 ball = ankle + q * g.ball_from_ankle_m;
  const quat qt = q * glm::angleAxis(toe_bend, vec3(1, 0, 0));
  const vec3 toe = ball + qt * g.toe_from_ball_m;
  const vec3 down = vec3(0, -g.sole_below_ball_m, 0);
  const float heel = (ankle + q * g.heel_from_ankle_m).y;
  return std::min({heel, (ball + q * down).y, (toe + qt * down).y});
}

float swing_progress(float u, float ease_exponent) {
  return smoothstep01(std::pow(clamp01(u), ease_exponent));
}

float swing_bump(float u) {
  u = clamp01(u);
  // Warped so the top comes at u ~ 0.43: the knee folds early in the swing.
  const float w = u + 0.3f * u * (1.0f - u);
  return std::sin(kPi * w);
}

vec3 rolled_ankle(const FootGeometry& g, vec2 ankle_xz_m, float flat_yaw_rad, float yaw_rad,
                  float pitch_rad) {
  const vec3 flat = from_ground(ankle_xz_m, g.ankle_height_m);
  const vec3 ball = flat + foot_rot(flat_yaw_rad, 0.0f) * g.ball_from_ankle_m;
  return ball + foot_rot(yaw_rad, pitch_rad) * -g.ball_from_ankle_m;
}

FootVia via_between(const FootPlant& lift, const FootPlant& land, float time_s, float u,
                    const FootGeometry& g, float ease_exponent) {
  const SegmentEnd a = lift_state(lift, g);
  const SegmentEnd b = land_state(land, g);
  const float w = swing_progress(u, ease_exponent);
  return {time_s, u, lerp(a.base, b.base, w), lerp_angle(a.yaw, b.yaw, w), lift.lift_pitch_rad};
}

FootSample sample_foot(const FootTimeline& keys, float t, const FootGeometry& g, float outward_sign,
                       float load_in_s, const std::function<SwingShape(float)>& shape_at,
                       const PlacementAt& root_at) {
  assert(!keys.empty());
  FootSample out;
  // The key covering t, or the pair around it.
  size_t i = 0;
  while (i + 1 < keys.size() && keys[i].end_s() < t) ++i;
  const FootKey& k = keys[i];
  if (!k.is_via && t >= k.plant.land_s && t <= k.plant.lift_s) {
    const FootPlant& p = k.plant;
    const float q = p.heel_off_s < p.lift_s ? (t - p.heel_off_s) / (p.lift_s - p.heel_off_s) : 0.0f;
    const float pitch = t > p.heel_off_s ? p.lift_pitch_rad * heel_roll(q) : 0.0f;
    out.yaw_rad = p.yaw_at(t);
    out.ankle_m = rolled_ankle(g, p.ankle_xz_m, p.yaw_rad, out.yaw_rad, pitch);
    out.pitch_rad = pitch;
    out.toe_bend_rad = -pitch;
    out.load = load_of(p, t, load_in_s);
    out.planted = true;
    return out;
  }
  // Swinging from keys[i-1] to k when t is before k, else from k to the next key. A via is the
  // same state from either side, so a via that ends the timeline is reached from the left.
  const bool before_k = t < k.start_s() || (k.is_via && i + 1 == keys.size());
  const size_t from = (before_k && i > 0) ? i - 1 : i;
  assert(from + 1 < keys.size() && "foot timeline does not cover the clip");
  const FootKey& ka = keys[from];
  const FootKey& kb = keys[from + 1];
  const SegmentEnd a = ka.is_via ? via_state(ka.via) : lift_state(ka.plant, g);
  const SegmentEnd b = kb.is_via ? via_state(kb.via) : land_state(kb.plant, g);
  const float span = std::max(b.time - a.time, 1e-4f);
  const float u = lerp(a.u, b.u, clamp01((t - a.time) / span));
  const float e = shape_at(0.5f * (a.time + b.time)).ease_exponent;
  const SwingShape shape = shape_at(t);
  const float pa = swing_progress(a.u, e), pb = swing_progress(b.u, e);
  const float w = pb > pa ? (swing_progress(u, e) - pa) / (pb - pa) : clamp01((t - a.time) / span);
  const float lift_pitch = a.lift_pitch;  // A via carries the pitch its swing started with.

  // On a turning path the foot swings along an arc, not the chord: it bulges to the outside by
  // the sagitta of the root's turn over the segment, so the outside foot of a turn does not cut
  // across the planted one. sin^2 keeps the bulge (and its velocity) zero at both segment ends, so
  // swings split at a via join smoothly; straight paths get none.
  const Placement ra = root_at(a.time), rb = root_at(b.time), rt = root_at(t);
  const vec2 chord = ground(b.base) - ground(a.base);
  const float turn = rb.heading_rad - ra.heading_rad;
  const float length = glm::length(chord);
  vec2 bulge(0.0f);
  if (length > 1e-4f) {
    const vec2 right(-chord.y / length, chord.x / length);
    const float sw = std::sin(kPi * w);
    bulge = right * (0.5f * length * std::tan(0.25f * turn) * sw * sw);
  }
  out.yaw_rad = rt.heading_rad + lerp_angle(a.yaw - ra.heading_rad, b.yaw - rb.heading_rad, w);
  out.ankle_m = lerp(a.base, b.base, w) + from_ground(bulge, 0.0f);
  out.ankle_m.y += shape.height_m * swing_bump(u);
  out.ankle_m += left3(out.yaw_rad) * (outward_sign * shape.bow_m * std::sin(kPi * u));
  out.pitch_rad = swing_pitch(u, lift_pitch, shape.toe_up_rad);
  out.toe_bend_rad = swing_toe_bend(u, lift_pitch);
  // Keep the whole sole above the floor (the ankle rises if a pitched toe or heel would dip).
  const float clearance = sole_clearance(g, out.ankle_m, out.yaw_rad, out.pitch_rad, out.toe_bend_rad);
  if (clearance < 0.0f) out.ankle_m.y -= clearance;
  return out;
}

}  // namespace foresight::author

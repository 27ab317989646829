#include "terrain/procedural_walk.hpp"

#include "author/default_skeleton.hpp"
#include "author/rig.hpp"

#include <algorithm>
#include <cmath>

namespace foresight::terrain {

namespace {

// The swing is checked on t in [kSwingEdge, 1 - kSwingEdge]: the ends are the footholds themselves,
// which foothold_fit has already placed on (never under) the ground.
constexpr float kSwingEdge = 0.02f;
// Mid-swing clearance ramps in over this much of the step at each end.
constexpr float kClearanceRamp = 0.25f;
// Reach slack: the swing ankle may be this much beyond the straight leg before the step fails (the
// IK then straightens the leg and the foot trails the curve by at most this).
constexpr float kReachSlack_m = 0.03f;
// The pelvis never asks for a fully straight stance leg (the IK is singular there).
constexpr float kStraightLegFraction = 0.995f;

float leg_max(const WalkParams& p) { return (p.thigh_m + p.shin_m) * kStraightLegFraction; }

// Shortest hip-ankle distance the knee limit allows (law of cosines).
float leg_min(const WalkParams& p) {
  const float a = p.thigh_m, b = p.shin_m;
  return std::sqrt(std::max(0.0f, a * a + b * b + 2.0f * a * b * std::cos(p.max_knee_rad)));
}

float bezier1(float a, float b, float c, float d, float t) {
  const float u = 1.0f - t;
  return u * u * u * a + 3.0f * u * u * t * b + 3.0f * u * t * t * c + t * t * t * d;
}

vec2 bezier(const std::array<vec2, 4>& p, float t) {
  return {bezier1(p[0].x, p[1].x, p[2].x, p[3].x, t), bezier1(p[0].y, p[1].y, p[2].y, p[3].y, t)};
}

// Two-bone IK in the sagittal plane, knee forward. The distance is clamped into the leg's range, so
// the result is always finite (an out-of-range ankle is approached as closely as the leg can).
LegPose leg_ik(const WalkParams& p, vec2 hip, vec2 ankle, float foot_pitch_rad) {
  const vec2 v = ankle - hip;
  const float a = p.thigh_m, b = p.shin_m;
  const float d = std::clamp(glm::length(v), std::max(leg_min(p), 1e-4f), a + b - 1e-5f);
  const float cos_gamma = std::clamp((a * a + b * b - d * d) / (2.0f * a * b), -1.0f, 1.0f);
  const float cos_beta = std::clamp((a * a + d * d - b * b) / (2.0f * a * d), -1.0f, 1.0f);
  const float alpha = std::atan2(v.x, -v.y);  // Hip -> ankle from straight down, + forward.
  LegPose pose;
  pose.knee_rad = kPi - std::acos(cos_gamma);
  pose.hip_rad = alpha + std::acos(cos_beta);
  const float shin = pose.hip_rad - pose.knee_rad;  // Shin angle from straight down.
  pose.ankle_rad = foot_pitch_rad - shin;
  return pose;
}

// Knee and ankle of a leg hanging from `hip` with the given joint angles.
void leg_fk_from_hip(const WalkParams& p, vec2 hip, const LegPose& pose, vec2& knee, vec2& ankle) {
  const float shin = pose.hip_rad - pose.knee_rad;
  knee = hip + p.thigh_m * vec2(std::sin(pose.hip_rad), -std::cos(pose.hip_rad));
  ankle = knee + p.shin_m * vec2(std::sin(shin), -std::cos(shin));
}

// Hip of a leg standing on `ankle` with the given joint angles (the stance leg: foot planted).
vec2 leg_fk_from_ankle(const WalkParams& p, vec2 ankle, const LegPose& pose, vec2& knee) {
  const float shin = pose.hip_rad - pose.knee_rad;
  knee = ankle - p.shin_m * vec2(std::sin(shin), -std::cos(shin));
  return knee - p.thigh_m * vec2(std::sin(pose.hip_rad), -std::cos(pose.hip_rad));
}

LegPose lerp_pose(const LegPose& a, const LegPose& b, float t) {
  return {a.hip_rad + (b.hip_rad - a.hip_rad) * t, a.knee_rad + (b.knee_rad - a.knee_rad) * t,
          a.ankle_rad + (b.ankle_rad - a.ankle_rad) * t};
}

// Stance joints at a phase: piecewise linear between the key frames.
LegPose stance_pose_at(const WalkStep& step, float phase) {
  const WalkKeyFrame& k0 = step.keys[0];
  const WalkKeyFrame& k1 = step.keys[1];
  const WalkKeyFrame& k2 = step.keys[2];
  if (phase <= k1.phase)
    return lerp_pose(k0.stance, k1.stance, (phase - k0.phase) / std::max(k1.phase - k0.phase, 1e-6f));
  return lerp_pose(k1.stance, k2.stance, (phase - k1.phase) / std::max(k2.phase - k1.phase, 1e-6f));
}

// Inverse of the smoothstep 3t^2 - 2t^3 on [0, 1] (the swing curve's x progress).
float smoothstep_inverse(float y) {
  return 0.5f - std::sin(std::asin(std::clamp(1.0f - 2.0f * y, -1.0f, 1.0f)) / 3.0f);
}

// Phase -> curve parameter: piecewise linear so that the swing ankle passes the stance ankle at
// the passing key frame (phase 0.5), whatever the two step lengths. Without it a short step
// followed by a long one has the foot race ahead of the pelvis out of the leg's reach.
float swing_param_at(const WalkStep& step, float phase) {
  const float tp = step.swing_param_at_passing;
  return phase < 0.5f ? 2.0f * phase * tp : tp + (2.0f * phase - 1.0f) * (1.0f - tp);
}

// The swing foot rolls from its lift-off pitch to level, and to its landing pitch at the end.
constexpr float kRoll = 0.15f;
float swing_pitch_at(const Foothold& rear, const Foothold& land, float t) {
  return t < 0.5f ? rear.pitch_rad * std::max(0.0f, 1.0f - t / kRoll)
                  : land.pitch_rad * std::max(0.0f, 1.0f - (1.0f - t) / kRoll);
}

vec2 ankle_of(const Foothold& f, const WalkParams& p) { return {f.x_m, f.sole_y_m + p.ankle_height_m}; }

// Highest pelvis both planted ankles reach (each leg at most straight) at pelvis x, or NaN when a
// foot is horizontally out of reach.
float double_support_pelvis_cap(const WalkParams& p, vec2 a, vec2 b, float x) {
  const float l = (p.thigh_m + p.shin_m) * p.double_support_leg_fraction;
  const float dxa = x - a.x, dxb = x - b.x;
  if (std::abs(dxa) >= l || std::abs(dxb) >= l) return NAN;
  return p.hip_below_pelvis_m +
         std::min(a.y + std::sqrt(l * l - dxa * dxa), b.y + std::sqrt(l * l - dxb * dxb));
}

bool within_leg_range(const WalkParams& p, vec2 hip, vec2 ankle, float slack) {
  const float d = glm::length(ankle - hip);
  return d <= p.thigh_m + p.shin_m + slack && d >= leg_min(p) - 1e-4f;
}

}  // namespace

WalkParams walk_params_from_default_skeleton() {
  const Skeleton skeleton = author::default_skeleton();
  const author::Rig rig = author::rig_from_skeleton(skeleton);
  WalkParams p;
  if (!author::rig_valid(skeleton, rig)) return p;  // The defaults are the same numbers.
  const author::LimbRig& leg = rig.leg[author::kLeft];
  p.thigh_m = leg.upper_m;
  p.shin_m = leg.lower_m;
  p.ankle_height_m = rig.ankle_height_m;
  p.toe_front_m = rig.ball_from_ankle_m.z + rig.toe_from_ball_m.z;
  p.hip_below_pelvis_m = -skeleton.rest_offsets_m[static_cast<std::size_t>(leg.root)].y;
  return p;
}

const char* step_kind_name(StepKind kind) {
  switch (kind) {
    case StepKind::kLevel: return "level";
    case StepKind::kUphill: return "uphill";
    case StepKind::kDownhill: return "downhill";
  }
  return "?";
}

const char* walk_status_name(WalkStatus status) {
  switch (status) {
    case WalkStatus::kOk: return "ok";
    case WalkStatus::kOutsideProfile: return "outside-profile";
    case WalkStatus::kFootInGap: return "foot-in-gap";
    case WalkStatus::kFootholdUneven: return "foothold-uneven";
    case WalkStatus::kStepTooHigh: return "step-too-high";
    case WalkStatus::kStepTooLow: return "step-too-low";
    case WalkStatus::kNoClearance: return "no-clearance";
    case WalkStatus::kUnreachable: return "unreachable";
  }
  return "?";
}

WalkStatus foothold_fit(const GroundProfile& profile, const WalkParams& params, float x_m,
                        Foothold& out) {
  const int i0 = profile.index_at(x_m - params.heel_back_m);
  const int i1 = profile.index_at(x_m + params.toe_front_m);
  if (i0 < 0 || i1 < 0) return WalkStatus::kOutsideProfile;
  const float* h = profile.height_m.data();
  for (int i = i0; i <= i1; ++i)
    if (std::isnan(h[i])) return WalkStatus::kFootInGap;
  // The sole line through the ground at heel and toe, then raised so nothing pokes through it.
  const float dx = std::max(static_cast<float>(i1 - i0) * profile.spacing_m, profile.spacing_m);
  const float slope = (h[i1] - h[i0]) / dx;
  if (std::abs(std::atan(slope)) > params.foot_max_pitch_rad) return WalkStatus::kFootholdUneven;
  float raise = -INFINITY;
  for (int i = i0; i <= i1; ++i)
    raise = std::max(raise, h[i] - (h[i0] + slope * static_cast<float>(i - i0) * profile.spacing_m));
  float dip = 0.0f;
  for (int i = i0; i <= i1; ++i)
    dip = std::max(dip, h[i0] + raise + slope * static_cast<float>(i - i0) * profile.spacing_m - h[i]);
  if (dip > params.foot_max_gap_m) return WalkStatus::kFootholdUneven;
  // Sample centres: cell i is centred at (i + 0.5) * spacing.
  const float x0 = (static_cast<float>(i0) + 0.5f) * profile.spacing_m;
  out.x_m = x_m;
  out.sole_y_m = h[i0] + raise + slope * (x_m - x0);
  out.pitch_rad = std::atan(slope);
  return WalkStatus::kOk;
}

WalkStatus walk_step_plan(const GroundProfile& profile, const WalkParams& p, const Foothold& rear,
                          const Foothold& stance, const Foothold& land, WalkStep& out) {
  // Category (Fig. 4) from the height change stance -> landing.
  const float dh = land.sole_y_m - stance.sole_y_m;
  if (dh > p.max_step_up_m) return WalkStatus::kStepTooHigh;
  if (dh < -p.max_step_down_m) return WalkStatus::kStepTooLow;
  const StepKind kind = dh > p.level_threshold_m    ? StepKind::kUphill
                        : dh < -p.level_threshold_m ? StepKind::kDownhill
                                                    : StepKind::kLevel;
  const vec2 a_rear = ankle_of(rear, p), a_stance = ankle_of(stance, p), a_land = ankle_of(land, p);

  // Key frame pelvis positions. Double support: over the lower foot's walking height, capped by
  // what both legs reach. Uphill this keeps the pelvis low at landing (the front leg is the bent
  // one); downhill the higher rear leg bends. The formula depends only on the two footholds, so
  // K2 of one step equals K0 of the next and consecutive steps join without a jump.
  const auto double_support = [&](vec2 a, vec2 b, float sole_a, float sole_b, vec2& pelvis) {
    pelvis.x = 0.5f * (a.x + b.x);
    const float cap = double_support_pelvis_cap(p, a, b, pelvis.x);
    if (std::isnan(cap)) return false;
    pelvis.y = std::min(std::min(sole_a, sole_b) + p.pelvis_height_m, cap);
    return true;
  };
  WalkStep step;
  step.kind = kind;
  step.rear = rear;
  step.stance = stance;
  step.land = land;
  step.keys[0].phase = 0.0f;
  step.keys[1].phase = 0.5f;
  step.keys[2].phase = 1.0f;
  if (!double_support(a_rear, a_stance, rear.sole_y_m, stance.sole_y_m, step.keys[0].pelvis_m) ||
      !double_support(a_stance, a_land, stance.sole_y_m, land.sole_y_m, step.keys[2].pelvis_m))
    return WalkStatus::kUnreachable;
  // Passing: the pelvis over the stance ankle; downhill the stance knee flexes first.
  const float straight = a_stance.y + p.hip_below_pelvis_m + leg_max(p);
  float pass_y = stance.sole_y_m + p.pelvis_height_m;
  if (kind == StepKind::kDownhill) pass_y += 0.5f * dh;
  step.keys[1].pelvis_m = {a_stance.x, std::min(pass_y, straight)};

  // Swing ankle curve: inner control points straight above the ends (the foot lifts before it
  // travels), at a common height Y. The sole's height at t over any ground cell is linear in Y, so
  // the lowest Y that clears every (sample, cell) pair is a maximum of ratios: the paper's
  // iterative raising of the control points, solved in one pass.
  const vec2 hi_end = a_rear.y > a_land.y ? a_rear : a_land;
  float y_ctrl = hi_end.y + p.swing_min_lift_m;
  const int n = std::clamp(p.swing_samples, 2, 64);
  const auto sample_t = [&](int k) {
    return kSwingEdge + (1.0f - 2.0f * kSwingEdge) * static_cast<float>(std::clamp(k, 0, n - 1)) /
                            static_cast<float>(n - 1);
  };
  const auto ankle_x = [&](float t) {
    const float u = 1.0f - t;
    return a_rear.x * (u * u * u + 3.0f * u * u * t) + a_land.x * (3.0f * u * t * t + t * t * t);
  };
  for (int k = 0; k < n; ++k) {
    const float t = sample_t(k);
    const float u = 1.0f - t;
    const float b0 = u * u * u, b12 = 3.0f * u * t, b3 = t * t * t;  // b1 + b2 = 3ut(u + t).
    const float x = ankle_x(t);
    // The cells the foot sweeps from the previous sample to the next one: the curve's height is
    // unimodal, so between samples the sole is above the lower of the two ends; checking the swept
    // cells at every sample keeps thin edges from slipping between samples.
    const int i0 = profile.index_at(ankle_x(sample_t(k - 1)) - p.heel_back_m);
    const int i1 = profile.index_at(ankle_x(sample_t(k + 1)) + p.toe_front_m);
    if (i0 < 0 || i1 < 0) return WalkStatus::kOutsideProfile;
    const float tan_pitch = std::tan(swing_pitch_at(rear, land, t));
    const float ramp = std::min({1.0f, t / kClearanceRamp, u / kClearanceRamp});
    // Highest ground relative to the pitched sole over the swept cells, then one division.
    // NaN (a gap: nothing to hit) drops out of std::max.
    const float* h = profile.height_m.data();
    float worst = -INFINITY;
    if (tan_pitch == 0.0f) {  // Mid-swing the foot is level: a plain maximum.
      for (int i = i0; i <= i1; ++i) worst = std::max(worst, h[i]);
    } else {
      // Sole over a cell = ankle - ankle height + (cell - ankle x) * tan(pitch), the offset
      // clamped to the foot (cells swept beyond it are checked at the sole's end).
      const float first_dx = (static_cast<float>(i0) + 0.5f) * profile.spacing_m - x;
      for (int i = i0; i <= i1; ++i) {
        const float dx = std::clamp(first_dx + static_cast<float>(i - i0) * profile.spacing_m,
                                    -p.heel_back_m, p.toe_front_m);
        worst = std::max(worst, h[i] - dx * tan_pitch);
      }
    }
    if (std::isinf(worst)) continue;  // Only gap under the foot.
    const float need_ankle = worst + p.swing_clearance_m * ramp + p.ankle_height_m;
    y_ctrl = std::max(y_ctrl, (need_ankle - (b0 * a_rear.y + b3 * a_land.y)) / b12);
  }
  step.lift_m = y_ctrl - hi_end.y;
  if (step.lift_m > p.swing_max_lift_m) return WalkStatus::kNoClearance;
  step.swing_ankle_bezier_m = {a_rear, vec2(a_rear.x, y_ctrl), vec2(a_land.x, y_ctrl), a_land};
  const float span = a_land.x - a_rear.x;
  step.swing_param_at_passing =
      span > 1e-4f ? std::clamp(smoothstep_inverse((a_stance.x - a_rear.x) / span), 0.02f, 0.98f) : 0.5f;

  // Key frame joints: the stance leg by IK to its planted ankle, the swing leg to its curve.
  const vec2 hip_off{0.0f, p.hip_below_pelvis_m};
  const vec2 swing_at_key[3] = {a_rear, bezier(step.swing_ankle_bezier_m, step.swing_param_at_passing),
                                a_land};
  const float swing_pitch_at_key[3] = {rear.pitch_rad, 0.0f, land.pitch_rad};
  for (int k = 0; k < 3; ++k) {
    WalkKeyFrame& key = step.keys[static_cast<std::size_t>(k)];
    const vec2 hip = key.pelvis_m - hip_off;
    if (!within_leg_range(p, hip, a_stance, 1e-3f)) return WalkStatus::kUnreachable;
    key.stance = leg_ik(p, hip, a_stance, stance.pitch_rad);
    key.swing = leg_ik(p, hip, swing_at_key[k], swing_pitch_at_key[k]);
  }
  // The swing ankle must stay within the leg's reach from the interpolated pelvis (checked at half
  // the clearance samples: the reach changes slowly, and this is the costly part, 4 sines each).
  const int n_reach = std::max(2, n / 2);
  for (int k = 1; k < n_reach; ++k) {
    const float t = static_cast<float>(k) / static_cast<float>(n_reach);
    vec2 knee;
    const vec2 hip = leg_fk_from_ankle(p, a_stance, stance_pose_at(step, t), knee);
    if (!within_leg_range(p, hip, bezier(step.swing_ankle_bezier_m, swing_param_at(step, t)),
                          kReachSlack_m))
      return WalkStatus::kUnreachable;
  }
  out = step;
  return WalkStatus::kOk;
}

void walk_step_sample(const WalkStep& step, const WalkParams& p, float phase, WalkFrame& out) {
  const float t = std::clamp(std::isnan(phase) ? 0.0f : phase, 0.0f, 1.0f);
  const vec2 a_stance = ankle_of(step.stance, p);
  out.stance = stance_pose_at(step, t);
  const vec2 hip = leg_fk_from_ankle(p, a_stance, out.stance, out.stance_knee_m);
  out.pelvis_m = hip + vec2(0.0f, p.hip_below_pelvis_m);
  out.stance_ankle_m = a_stance;
  const float u = swing_param_at(step, t);
  out.swing_foot_pitch_rad = swing_pitch_at(step.rear, step.land, u);
  const vec2 target = bezier(step.swing_ankle_bezier_m, u);
  out.swing = leg_ik(p, hip, target, out.swing_foot_pitch_rad);
  leg_fk_from_hip(p, hip, out.swing, out.swing_knee_m, out.swing_ankle_m);
  const vec2 sole = out.swing_ankle_m - vec2(0.0f, p.ankle_height_m);
  const float tan_pitch = std::tan(out.swing_foot_pitch_rad);
  out.swing_heel_m = sole + vec2(-p.heel_back_m, -p.heel_back_m * tan_pitch);
  out.swing_toe_m = sole + vec2(p.toe_front_m, p.toe_front_m * tan_pitch);
}

}  // namespace foresight::terrain

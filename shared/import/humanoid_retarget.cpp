#include "import/humanoid_retarget.hpp"

#include "anim/fk.hpp"

#include <algorithm>
#include <array>

namespace foresight {
namespace {

using Points = std::array<vec3, kCanonJointCount>;

// Arc fractions of the canonical Spine and Spine1 along pelvis -> chest (0.10 and 0.23 of 0.37 m).
constexpr float kSpineFraction = 0.10f / 0.37f;
constexpr float kSpine1Fraction = 0.23f / 0.37f;

vec3 along_polyline(std::span<const vec3> pts, float fraction) {
  float total = 0.0f;
  for (size_t i = 1; i < pts.size(); ++i) total += glm::length(pts[i] - pts[i - 1]);
  float left = fraction * total;
  for (size_t i = 1; i < pts.size(); ++i) {
    const float l = glm::length(pts[i] - pts[i - 1]);
    if (left <= l && l > 0.0f) return glm::mix(pts[i - 1], pts[i], left / l);
    left -= l;
  }
  return pts.back();
}

vec3 safe_normalize(vec3 v, vec3 fallback) {
  const float l = glm::length(v);
  return l > 1e-8f ? v / l : fallback;
}

// The canonical joints' positions in one frame of the capture (global positions `s`).
Points canonical_points(const HumanoidMap& m, const vec3* s) {
  Points c{};
  c[kCanonHips] = s[m.pelvis];
  std::array<vec3, 64> spine{};
  size_t count = 0;
  spine[count++] = s[m.pelvis];
  for (int j : m.spine)
    if (count + 1 < spine.size()) spine[count++] = s[j];
  spine[count++] = s[m.chest];
  const std::span<const vec3> chain(spine.data(), count);
  c[kCanonSpine] = along_polyline(chain, kSpineFraction);
  c[kCanonSpine1] = along_polyline(chain, kSpine1Fraction);
  c[kCanonChest] = s[m.chest];
  c[kCanonNeck] = s[m.neck];
  c[kCanonHead] = s[m.head];
  c[kCanonHeadTop] = m.head_top >= 0 ? s[m.head_top] : s[m.head] + 1.5f * (s[m.head] - s[m.neck]);
  const vec3 hip_left = s[m.thigh[0]] - s[m.thigh[1]];
  const vec3 pelvis_up = c[kCanonSpine] - c[kCanonHips];
  const vec3 forward = safe_normalize(glm::cross(hip_left, pelvis_up), vec3(0, 0, 1));
  for (int side = 0; side < 2; ++side) {
    const int arm = side == 0 ? kCanonLeftShoulder : kCanonRightShoulder;
    c[arm] = m.clavicle[side] >= 0 ? s[m.clavicle[side]] : glm::mix(s[m.chest], s[m.upper_arm[side]], 0.2f);
    c[arm + 1] = s[m.upper_arm[side]];
    c[arm + 2] = s[m.forearm[side]];
    c[arm + 3] = s[m.hand[side]];
    c[arm + 4] = m.hand_end[side] >= 0 ? s[m.hand_end[side]] : s[m.hand[side]] + 0.3f * (s[m.hand[side]] - s[m.forearm[side]]);
    const int leg = side == 0 ? kCanonLeftUpLeg : kCanonRightUpLeg;
    c[leg] = s[m.thigh[side]];
    c[leg + 1] = s[m.shin[side]];
    c[leg + 2] = s[m.foot[side]];
    const float k = glm::length(s[m.shin[side]] - s[m.thigh[side]]) / 0.42f;  // canonical thigh 0.42 m
    c[leg + 3] = m.toe[side] >= 0 ? s[m.toe[side]] : s[m.foot[side]] + k * (0.13f * forward - vec3(0, 0.055f, 0));
    vec3 along = c[leg + 3] - c[leg + 2];
    along.y = 0.0f;
    c[leg + 4] = m.toe_end[side] >= 0 ? s[m.toe_end[side]] : c[leg + 3] + 0.06f * k * safe_normalize(along, forward);
  }
  return c;
}

// The reference directions a joint's twist is taken from: the body's left, up and forward at the
// pelvis and at the chest, in the capture (from its points) or in the canonical rest pose.
struct BodyAxes {
  vec3 hip_left, pelvis_up, pelvis_fwd, chest_left, chest_up, chest_fwd;
};

BodyAxes axes_of(const Points& c) {
  BodyAxes a;
  a.hip_left = c[kCanonLeftUpLeg] - c[kCanonRightUpLeg];
  a.pelvis_up = c[kCanonSpine] - c[kCanonHips];
  a.pelvis_fwd = glm::cross(a.hip_left, a.pelvis_up);
  a.chest_left = c[kCanonLeftShoulder] - c[kCanonRightShoulder];
  a.chest_up = c[kCanonNeck] - c[kCanonChest];
  a.chest_fwd = glm::cross(a.chest_left, a.chest_up);
  return a;
}

const BodyAxes kRestAxes{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

// `preferred` made perpendicular to the bone, blending to `fallback` where the bone nearly runs
// along it (an arm raised sideways, a foot pointing down), so the twist never flips.
vec3 twist_reference(vec3 bone, vec3 preferred, vec3 fallback) {
  const vec3 d = safe_normalize(bone, vec3(0, 1, 0));
  const vec3 a = safe_normalize(preferred, vec3(1, 0, 0)), b = safe_normalize(fallback, vec3(0, 0, 1));
  const vec3 ap = a - glm::dot(a, d) * d, bp = b - glm::dot(b, d) * d;
  const float w = glm::smoothstep(0.25f, 0.5f, glm::length(ap));
  return w * safe_normalize(ap, vec3(0)) + (1.0f - w) * safe_normalize(bp, vec3(0));
}

vec3 twist_reference_for(int joint, vec3 bone, const BodyAxes& a) {
  switch (joint) {
    case kCanonHips: return twist_reference(bone, a.hip_left, a.pelvis_fwd);
    case kCanonSpine: return twist_reference(bone, glm::mix(a.hip_left, a.chest_left, 0.33f), a.chest_fwd);
    case kCanonSpine1: return twist_reference(bone, glm::mix(a.hip_left, a.chest_left, 0.67f), a.chest_fwd);
    case kCanonChest: case kCanonNeck: case kCanonHead: return twist_reference(bone, a.chest_left, a.chest_fwd);
    case kCanonLeftShoulder: case kCanonRightShoulder: return twist_reference(bone, a.chest_up, a.chest_fwd);
    case kCanonLeftArm: case kCanonLeftForeArm: case kCanonLeftHand:
    case kCanonRightArm: case kCanonRightForeArm: case kCanonRightHand:
      return twist_reference(bone, a.chest_left, a.chest_fwd);
    case kCanonLeftFoot: case kCanonLeftToeBase: case kCanonRightFoot: case kCanonRightToeBase:
      return twist_reference(bone, a.hip_left, a.pelvis_up);
    default: return twist_reference(bone, a.hip_left, a.pelvis_fwd);  // thighs and shins
  }
}

glm::mat3 frame_of(vec3 bone, vec3 reference) {
  const vec3 x = safe_normalize(bone, vec3(0, 1, 0));
  const vec3 y = safe_normalize(reference - glm::dot(reference, x) * x, glm::abs(x.x) < 0.9f ? vec3(1, 0, 0) : vec3(0, 1, 0));
  return glm::mat3(x, y, glm::cross(x, y));
}

// Rest bone direction of every canonical joint (from the built-in proportions).
std::array<vec3, kCanonJointCount> rest_bones() {
  const Skeleton rest = canonical_skeleton();
  std::array<vec3, kCanonJointCount> out{};
  for (int j = 0; j < kCanonJointCount; ++j) {
    const int c = canonical_primary_child(j);
    out[static_cast<size_t>(j)] = c >= 0 ? glm::normalize(rest.rest_offsets_m[static_cast<size_t>(c)]) : vec3(0);
  }
  return out;
}

// Global rotation of every non-End-Site canonical joint for one frame's points.
void global_rotations(const Points& c, std::array<quat, kCanonJointCount>& out) {
  static const std::array<vec3, kCanonJointCount> rest = rest_bones();
  const BodyAxes axes = axes_of(c);
  for (int j = 0; j < kCanonJointCount; ++j) {
    const int child = canonical_primary_child(j);
    if (child < 0) {
      out[static_cast<size_t>(j)] = out[static_cast<size_t>(j - 1)];
      continue;
    }
    const vec3 bone = c[static_cast<size_t>(child)] - c[static_cast<size_t>(j)];
    const vec3 rest_bone = rest[static_cast<size_t>(j)];
    const glm::mat3 now = frame_of(bone, twist_reference_for(j, bone, axes));
    const glm::mat3 then = frame_of(rest_bone, twist_reference_for(j, rest_bone, kRestAxes));
    out[static_cast<size_t>(j)] = glm::normalize(glm::quat_cast(now * glm::transpose(then)));
  }
}

}  // namespace

Skeleton canonical_skeleton_from_capture(const HumanoidMap& map, std::span<const vec3> positions) {
  const Points c = canonical_points(map, positions.data());
  std::array<quat, kCanonJointCount> global{};
  global_rotations(c, global);
  Skeleton out = canonical_skeleton();
  for (int j = 1; j < kCanonJointCount; ++j) {
    const int parent = out.parents[static_cast<size_t>(j)];
    const vec3 bone = c[static_cast<size_t>(j)] - c[static_cast<size_t>(parent)];
    vec3& offset = out.rest_offsets_m[static_cast<size_t>(j)];
    if (canonical_primary_child(parent) == j)
      offset = glm::normalize(offset) * glm::length(bone);  // canonical direction, captured length
    else
      offset = glm::inverse(global[static_cast<size_t>(parent)]) * bone;  // hips, clavicles: as captured
  }
  out.rest_offsets_m[kCanonHips] = vec3(0, c[kCanonHips].y - std::min(c[kCanonLeftToeBase].y, c[kCanonRightToeBase].y) +
                                                 kRestBallHeightM, 0);
  return out;
}

HumanoidMap canonical_humanoid_map() {
  HumanoidMap m;
  m.pelvis = kCanonHips;
  m.spine = {kCanonSpine, kCanonSpine1};
  m.chest = kCanonChest;
  m.neck = kCanonNeck;
  m.head = kCanonHead;
  m.head_top = kCanonHeadTop;
  for (int side = 0; side < 2; ++side) {
    const int arm = side == 0 ? kCanonLeftShoulder : kCanonRightShoulder;
    m.clavicle[side] = arm, m.upper_arm[side] = arm + 1, m.forearm[side] = arm + 2;
    m.hand[side] = arm + 3, m.hand_end[side] = arm + 4;
    const int leg = side == 0 ? kCanonLeftUpLeg : kCanonRightUpLeg;
    m.thigh[side] = leg, m.shin[side] = leg + 1, m.foot[side] = leg + 2;
    m.toe[side] = leg + 3, m.toe_end[side] = leg + 4;
  }
  return m;
}

float canonical_leg_length(const Skeleton& canonical) {
  float sum = 0.0f;
  for (int j : {kCanonLeftLeg, kCanonLeftFoot, kCanonRightLeg, kCanonRightFoot})
    sum += glm::length(canonical.rest_offsets_m[static_cast<size_t>(j)]);
  return 0.5f * sum;
}

void retarget_to_canonical(const Skeleton& source, const Clip& clip, const HumanoidMap& map,
                           const Skeleton& canonical, float root_scale, Clip& out) {
  std::vector<vec3> positions;
  fk_clip_positions(source, clip, positions);
  const int n = source.num_joints();
  Clip result;
  result.name = clip.name;
  result.fps = clip.fps;
  result.resize(canonical, clip.num_frames);
  std::array<quat, kCanonJointCount> global{};
  for (int f = 0; f < clip.num_frames; ++f) {
    const Points c = canonical_points(map, positions.data() + static_cast<size_t>(f) * n);
    global_rotations(c, global);
    std::span<vec3> pos = result.frame_pos(f);
    std::span<quat> rot = result.frame_rot(f);
    pos[kCanonHips] = c[kCanonHips] * root_scale;
    rot[kCanonHips] = global[kCanonHips];
    for (int j = 1; j < kCanonJointCount; ++j) {
      const int parent = canonical.parents[static_cast<size_t>(j)];
      rot[static_cast<size_t>(j)] = canonical.is_end_site[static_cast<size_t>(j)]
                                        ? quat(1, 0, 0, 0)
                                        : glm::normalize(glm::inverse(global[static_cast<size_t>(parent)]) *
                                                         global[static_cast<size_t>(j)]);
    }
  }
  // Quaternion signs continuous over time (blending and resampling take the short way).
  for (int f = 1; f < result.num_frames; ++f)
    for (int j = 0; j < kCanonJointCount; ++j) {
      quat& q = result.frame_rot(f)[static_cast<size_t>(j)];
      if (glm::dot(q, result.frame_rot(f - 1)[static_cast<size_t>(j)]) < 0.0f) q = -q;
    }
  out = std::move(result);
}

}  // namespace foresight

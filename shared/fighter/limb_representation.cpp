#include "fighter/limb_representation.hpp"

#include "anim/fk.hpp"
#include "fighter/morphology.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace foresight {
namespace {

enum Role : int8_t { kInherit, kSegment, kSpine, kArmUpper, kArmLower, kLegUpper, kLegLower };

constexpr quat kIdentity{1.0f, 0.0f, 0.0f, 0.0f};
// Feet whose contact is this far above its flat height (or lower) count as grounded when deciding
// whether the pelvis must come down so the legs reach them; a kicking foot never pulls it down.
constexpr float kGroundedClearanceM = 0.12f;

vec3 safe_normalize(vec3 v, vec3 fallback) {
  const float l2 = glm::dot(v, v);
  return l2 > 1e-14f ? v / std::sqrt(l2) : fallback;
}

int first_child(const Skeleton& s, int joint) {
  for (int j = joint + 1; j < s.num_joints(); ++j)
    if (s.parents[static_cast<size_t>(j)] == joint) return j;
  return -1;
}

// Rotation-minimising swivel basis: the reference e0 (perpendicular to u0) carried by the smallest
// rotation taking u0 onto the limb axis u. Singular only for u = -u0 (an arm pointing straight up,
// a leg pointing straight up), where no fighting pose goes; a projected fixed reference would
// instead be singular both ways, e.g. for a punch straight ahead.
void swivel_basis(bool arm, vec3 u, vec3& e1, vec3& e2) {
  const vec3 u0(0.0f, -1.0f, 0.0f);
  const vec3 e0 = arm ? vec3(0.0f, 0.0f, -1.0f) : vec3(0.0f, 0.0f, 1.0f);  // elbow back, knee forward
  const float c = glm::dot(u0, u);
  const vec3 v = glm::cross(u0, u);
  vec3 r = c > -0.9999f ? e0 * c + glm::cross(v, e0) + v * (glm::dot(v, e0) / (1.0f + c)) : -e0;
  r -= u * glm::dot(r, u);
  e1 = safe_normalize(r, glm::abs(u.x) < 0.9f ? glm::normalize(glm::cross(u, vec3(1, 0, 0)))
                                               : glm::normalize(glm::cross(u, vec3(0, 1, 0))));
  e2 = glm::cross(u, e1);
}

vec3 swivel_direction(bool arm, vec3 u, float swivel_rad) {
  vec3 e1, e2;
  swivel_basis(arm, u, e1, e2);
  return e1 * std::cos(swivel_rad) + e2 * std::sin(swivel_rad);
}

float swivel_angle(bool arm, vec3 u, vec3 bend) {
  vec3 e1, e2;
  swivel_basis(arm, u, e1, e2);
  return std::atan2(glm::dot(bend, e2), glm::dot(bend, e1));
}

// The frame of `pose`'s spine at place u (0 = pelvis, 1 = neck), interpolating between joints.
quat spine_frame_at(const LimbPose& p, float u) {
  const int n = p.num_spine;
  if (n == 0) return glm::slerp(p.frame[kSegPelvis], p.frame[kSegNeck], u);
  for (int i = 0; i < n; ++i) {
    const float ui = p.spine_u[static_cast<size_t>(i)];
    if (std::abs(u - ui) < 1e-5f) return p.spine_frame[static_cast<size_t>(i)];
    if (u < ui) {
      const float u0 = i == 0 ? 0.0f : p.spine_u[static_cast<size_t>(i - 1)];
      const quat q0 = i == 0 ? p.frame[kSegPelvis] : p.spine_frame[static_cast<size_t>(i - 1)];
      return glm::slerp(q0, p.spine_frame[static_cast<size_t>(i)], (u - u0) / std::max(ui - u0, 1e-6f));
    }
  }
  const float ul = p.spine_u[static_cast<size_t>(n - 1)];
  return glm::slerp(p.spine_frame[static_cast<size_t>(n - 1)], p.frame[kSegNeck],
                    (u - ul) / std::max(1.0f - ul, 1e-6f));
}

void set_segment(SegmentAxes& axes, int joint, const quat* grot, vec3 aim_w, vec3 hint_w) {
  axes.joint = joint;
  axes.frame_local = glm::normalize(glm::inverse(grot[joint]) * frame_from_axes(aim_w, hint_w));
  axes.inv_frame_local = glm::inverse(axes.frame_local);
}

void set_limb(LimbAxes& axes, const FighterLimb& limb, const vec3* gpos, const quat* grot, vec3 fallback_bend) {
  const vec3 root = gpos[limb.root], mid = gpos[limb.mid], end = gpos[limb.end];
  const vec3 axis = safe_normalize(end - root, vec3(0, -1, 0));
  vec3 bend = (mid - root) - axis * glm::dot(mid - root, axis);
  if (glm::length(bend) < 0.01f * limb.length_m()) bend = fallback_bend - axis * glm::dot(fallback_bend, axis);
  bend = safe_normalize(bend, vec3(0, 0, 1));
  axes.upper_frame_local = glm::normalize(glm::inverse(grot[limb.root]) * frame_from_axes(mid - root, bend));
  axes.lower_frame_local = glm::normalize(glm::inverse(grot[limb.mid]) * frame_from_axes(end - mid, bend));
  axes.inv_upper_frame_local = glm::inverse(axes.upper_frame_local);
  axes.inv_lower_frame_local = glm::inverse(axes.lower_frame_local);
  axes.bend_upper_local = glm::inverse(grot[limb.root]) * bend;
}

// The limb's bend direction in a pose (perpendicular to the unit root -> end `axis`): where the
// middle joint actually is when the limb is bent (exact positions even for a ball-and-socket elbow),
// fading to the upper bone's calibrated bend as the limb straightens and the geometry says nothing.
vec3 pose_bend(vec3 root, vec3 mid, vec3 axis, quat upper_rot, vec3 bend_upper_local, float length) {
  vec3 from_frame = upper_rot * bend_upper_local;
  from_frame = safe_normalize(from_frame - axis * glm::dot(from_frame, axis), vec3(0, 0, 1));
  const vec3 geo = (mid - root) - axis * glm::dot(mid - root, axis);
  // Millimetres, not a fraction of the length: beyond 0.6 mm off the line the geometry is exact
  // (the round trip must stay within 1 mm); below 0.2 mm it is noise.
  (void)length;
  const float t = std::clamp((glm::length(geo) - 0.0002f) / 0.0004f, 0.0f, 1.0f);
  if (t <= 0.0f) return from_frame;
  return safe_normalize(glm::mix(from_frame, geo / glm::length(geo), t), geo / glm::length(geo));
}

void mark(LimbModel& m, int joint, Role role, int index) {
  if (joint < 0) return;
  m.role[static_cast<size_t>(joint)] = role;
  m.role_index[static_cast<size_t>(joint)] = static_cast<int8_t>(index);
}

}  // namespace

quat frame_from_axes(vec3 aim, vec3 hint) {
  const vec3 x = safe_normalize(aim, vec3(0, 1, 0));
  vec3 y = hint - x * glm::dot(hint, x);
  if (glm::dot(y, y) < 1e-12f) y = glm::abs(x.x) < 0.9f ? glm::cross(x, vec3(1, 0, 0)) : glm::cross(x, vec3(0, 1, 0));
  y = glm::normalize(y);
  return glm::quat_cast(glm::mat3(x, y, glm::cross(x, y)));
}

vec3 limb_swivel_direction(bool arm, vec3 axis_unit, float swivel_rad) {
  return swivel_direction(arm, axis_unit, swivel_rad);
}
float limb_swivel_angle(bool arm, vec3 axis_unit, vec3 bend_dir) { return swivel_angle(arm, axis_unit, bend_dir); }

void two_bone_positions(vec3 root_m, vec3 target_m, float upper_m, float lower_m, vec3 bend,
                        vec3& mid_m, vec3& end_m) {
  const vec3 to = target_m - root_m;
  const float dist = glm::length(to);
  const vec3 u = dist > 1e-7f ? to / dist : glm::normalize(glm::cross(bend, vec3(1, 0, 0)) + vec3(0, -1e-3f, 0));
  // At most straight, at least folded as far as the bones allow.
  const float d = std::clamp(dist, std::abs(upper_m - lower_m) + 1e-4f, upper_m + lower_m);
  const float x = (upper_m * upper_m + d * d - lower_m * lower_m) / (2.0f * d);
  const float h = std::sqrt(std::max(0.0f, upper_m * upper_m - x * x));
  mid_m = root_m + u * x + bend * h;
  end_m = root_m + u * d;
}

bool limb_model_build(const Skeleton& s, std::span<const vec3> calib_local_pos_m,
                      std::span<const quat> calib_local_rot, float contact_height_m,
                      float ankle_height_m, LimbModel& m, std::string& error) {
  m = LimbModel{};
  const int n = s.num_joints();
  if (n > kLimbMaxJoints) {
    error = "limb model: more than " + std::to_string(kLimbMaxJoints) + " joints";
    return false;
  }
  if (!fighter_rig_from_skeleton(s, m.rig, error)) return false;
  const FighterRig& rig = m.rig;
  if (static_cast<int>(rig.spine.size()) > kLimbMaxSpine) {
    error = "limb model: more than " + std::to_string(kLimbMaxSpine) + " spine joints";
    return false;
  }
  std::array<vec3, kLimbMaxJoints> gpos;
  std::array<quat, kLimbMaxJoints> grot;
  fk_pose(s, calib_local_pos_m, calib_local_rot, gpos, grot);

  const vec3 up(0, 1, 0);
  const vec3 hips_left = safe_normalize(gpos[rig.leg[0].root] - gpos[rig.leg[1].root], vec3(1, 0, 0));
  const vec3 shoulders_left = safe_normalize(gpos[rig.arm[0].root] - gpos[rig.arm[1].root], vec3(1, 0, 0));
  const vec3 forward = safe_normalize(glm::cross(hips_left, up), vec3(0, 0, 1));
  auto aim_to = [&](int joint, int distal) {
    if (distal >= 0) return gpos[distal] - gpos[joint];
    // No distal joint: continue the bone that ends here.
    return gpos[joint] - gpos[s.parents[static_cast<size_t>(joint)]];
  };

  m.role.assign(static_cast<size_t>(n), kInherit);
  m.role_index.assign(static_cast<size_t>(n), 0);
  // Pelvis and spine: aim up the chain, hint = the hips' (pelvis) or the shoulders' left.
  const int spine0 = rig.spine.front();
  set_segment(m.segment[kSegPelvis], 0, grot.data(), aim_to(0, spine0), hips_left);
  mark(m, 0, kSegment, kSegPelvis);
  float chain = 0.0f;
  std::array<float, kLimbMaxSpine> dist{};
  m.num_spine = static_cast<int>(rig.spine.size());
  for (int i = 0; i < m.num_spine; ++i) {
    const int j = rig.spine[static_cast<size_t>(i)];
    const int distal = i + 1 < m.num_spine ? rig.spine[static_cast<size_t>(i + 1)] : rig.neck;
    chain += glm::length(s.rest_offsets_m[static_cast<size_t>(j)]);
    dist[static_cast<size_t>(i)] = chain;
    set_segment(m.spine[static_cast<size_t>(i)], j, grot.data(), aim_to(j, distal), shoulders_left);
    mark(m, j, kSpine, i);
  }
  chain += glm::length(s.rest_offsets_m[static_cast<size_t>(rig.neck)]);
  for (int i = 0; i < m.num_spine; ++i) m.spine_u[static_cast<size_t>(i)] = dist[static_cast<size_t>(i)] / chain;

  set_segment(m.segment[kSegNeck], rig.neck, grot.data(), aim_to(rig.neck, rig.head), shoulders_left);
  mark(m, rig.neck, kSegment, kSegNeck);
  set_segment(m.segment[kSegHead], rig.head, grot.data(), aim_to(rig.head, first_child(s, rig.head)), shoulders_left);
  mark(m, rig.head, kSegment, kSegHead);
  for (int side = 0; side < 2; ++side) {
    const FighterLimb& arm = rig.arm[static_cast<size_t>(side)];
    const FighterLimb& leg = rig.leg[static_cast<size_t>(side)];
    const int clav = rig.clavicle[static_cast<size_t>(side)];
    if (clav > 0 && m.role[static_cast<size_t>(clav)] == kInherit) {
      set_segment(m.segment[kSegClavicleL + side], clav, grot.data(), aim_to(clav, arm.root), up);
      mark(m, clav, kSegment, kSegClavicleL + side);
    }
    set_segment(m.segment[kSegHandL + side], arm.end, grot.data(), aim_to(arm.end, first_child(s, arm.end)), shoulders_left);
    mark(m, arm.end, kSegment, kSegHandL + side);
    const int toe = rig.toe[static_cast<size_t>(side)];
    set_segment(m.segment[kSegFootL + side], leg.end, grot.data(),
                aim_to(leg.end, toe >= 0 ? toe : first_child(s, leg.end)), hips_left);
    mark(m, leg.end, kSegment, kSegFootL + side);
    if (toe >= 0) {
      set_segment(m.segment[kSegToeL + side], toe, grot.data(), aim_to(toe, first_child(s, toe)), hips_left);
      mark(m, toe, kSegment, kSegToeL + side);
    }
    set_limb(m.arm_axes[static_cast<size_t>(side)], arm, gpos.data(), grot.data(), -forward);
    set_limb(m.leg_axes[static_cast<size_t>(side)], leg, gpos.data(), grot.data(), forward);
    mark(m, arm.root, kArmUpper, side);
    mark(m, arm.mid, kArmLower, side);
    mark(m, leg.root, kLegUpper, side);
    mark(m, leg.mid, kLegLower, side);
    m.contact[static_cast<size_t>(side)] = toe >= 0 ? toe : leg.end;
    m.contact_height_m[static_cast<size_t>(side)] = toe >= 0 ? contact_height_m : ankle_height_m;
    m.arm_length_m[static_cast<size_t>(side)] = arm.length_m();
  }
  m.leg_length_m = 0.5f * (rig.leg[0].length_m() + rig.leg[1].length_m());
  const float hip_drop = gpos[0].y - 0.5f * (gpos[rig.leg[0].root].y + gpos[rig.leg[1].root].y);
  m.standing_pelvis_m = hip_drop + m.leg_length_m + ankle_height_m;
  return true;
}

bool limb_model_for_morphology(const Morphology& morph, LimbModel& model, std::string& error) {
  const Skeleton& s = morph.skeleton;
  const std::vector<quat> rot(static_cast<size_t>(s.num_joints()), kIdentity);
  return limb_model_build(s, s.rest_offsets_m, rot, morph.ball_height_m, morph.ankle_height_m, model, error);
}

bool limb_model_from_clip(const Skeleton& s, const Clip& clip, int calibration_frame, LimbModel& model,
                          std::string& error) {
  if (clip.num_joints != s.num_joints() || calibration_frame < 0 || calibration_frame >= clip.num_frames) {
    error = "limb model: the clip does not match the skeleton or has no such frame";
    return false;
  }
  FighterRig rig;
  if (!fighter_rig_from_skeleton(s, rig, error)) return false;
  std::vector<vec3> all;
  fk_clip_positions(s, clip, all);
  float contact = std::numeric_limits<float>::max(), ankle = contact;
  const int n = s.num_joints();
  for (int f = 0; f < clip.num_frames; ++f)
    for (int side = 0; side < 2; ++side) {
      const int a = rig.leg[static_cast<size_t>(side)].end;
      const int c = rig.toe[static_cast<size_t>(side)] >= 0 ? rig.toe[static_cast<size_t>(side)] : a;
      contact = std::min(contact, all[static_cast<size_t>(f) * n + c].y);
      ankle = std::min(ankle, all[static_cast<size_t>(f) * n + a].y);
    }
  return limb_model_build(s, clip.frame_pos(calibration_frame), clip.frame_rot(calibration_frame), contact,
                          ankle, model, error);
}

void limb_pose_encode(const Skeleton& s, const LimbModel& m, std::span<const vec3> local_pos_m,
                      std::span<const quat> local_rot, const Placement& root, LimbPose& out) {
  const int n = s.num_joints();
  assert(n <= kLimbMaxJoints);
  std::array<vec3, kLimbMaxJoints> gpos;
  std::array<quat, kLimbMaxJoints> grot;
  fk_pose(s, local_pos_m, local_rot, {gpos.data(), static_cast<size_t>(n)}, {grot.data(), static_cast<size_t>(n)});
  const Placement to_root = root.inverse();
  const quat unhead = quat_from_heading(-root.heading_rad);
  const float leg = m.leg_length_m;

  const vec3 pelvis = to_root.apply(gpos[0]);
  out.pelvis_n = vec3(pelvis.x / leg, (pelvis.y - m.standing_pelvis_m) / leg, pelvis.z / leg);
  for (int k = 0; k < kNumLimbSegments; ++k) {
    const SegmentAxes& a = m.segment[static_cast<size_t>(k)];
    out.frame[static_cast<size_t>(k)] = a.joint >= 0 ? glm::normalize(unhead * grot[a.joint] * a.frame_local) : kIdentity;
  }
  for (int side = 0; side < 2; ++side)  // No toe joint: the toes lie as the foot does.
    if (m.segment[kSegToeL + side].joint < 0) out.frame[kSegToeL + side] = out.frame[kSegFootL + side];
  out.num_spine = m.num_spine;
  for (int i = 0; i < m.num_spine; ++i) {
    const SegmentAxes& a = m.spine[static_cast<size_t>(i)];
    out.spine_frame[static_cast<size_t>(i)] = glm::normalize(unhead * grot[a.joint] * a.frame_local);
    out.spine_u[static_cast<size_t>(i)] = m.spine_u[static_cast<size_t>(i)];
  }
  for (int side = 0; side < 2; ++side) {
    const size_t si = static_cast<size_t>(side);
    const FighterLimb& arm = m.rig.arm[si];
    const vec3 reach = unhead * (gpos[arm.end] - gpos[arm.root]);
    out.arm_end_n[si] = reach / m.arm_length_m[si];
    const vec3 axis = safe_normalize(reach, vec3(0, -1, 0));
    const vec3 arm_bend = pose_bend(gpos[arm.root], gpos[arm.mid], glm::inverse(unhead) * axis, grot[arm.root],
                                    m.arm_axes[si].bend_upper_local, arm.length_m());
    out.arm_swivel_rad[si] = swivel_angle(true, axis, unhead * arm_bend);

    const FighterLimb& lg = m.rig.leg[si];
    const vec3 contact = to_root.apply(gpos[m.contact[si]]);
    out.leg_contact_n[si] = vec3(contact.x / leg, (contact.y - m.contact_height_m[si]) / leg, contact.z / leg);
    const vec3 leg_axis_w = safe_normalize(gpos[lg.end] - gpos[lg.root], vec3(0, -1, 0));
    const vec3 leg_bend = pose_bend(gpos[lg.root], gpos[lg.mid], leg_axis_w, grot[lg.root],
                                    m.leg_axes[si].bend_upper_local, lg.length_m());
    out.leg_swivel_rad[si] = swivel_angle(false, unhead * leg_axis_w, unhead * leg_bend);
  }
}

void limb_pose_decode(const Skeleton& s, const LimbModel& m, const LimbPose& p, const Placement& root,
                      const PoseSpans& out) {
  const int n = s.num_joints();
  assert(n <= kLimbMaxJoints && static_cast<int>(out.local_rot.size()) >= n);
  const quat head = quat_from_heading(root.heading_rad);
  const float leg = m.leg_length_m;
  auto segment_rot = [&](int k) {
    return head * p.frame[static_cast<size_t>(k)] * m.segment[static_cast<size_t>(k)].inv_frame_local;
  };

  // Pelvis, and the ankles the legs must reach (placed from the contact joint, so a planted ball of
  // the foot stays put whatever the foot length).
  vec3 pelvis = root.apply(vec3(p.pelvis_n.x * leg, m.standing_pelvis_m + p.pelvis_n.y * leg, p.pelvis_n.z * leg));
  const quat pelvis_rot = segment_rot(kSegPelvis);
  std::array<vec3, 2> ankle;
  std::array<quat, 2> foot_rot;
  for (int side = 0; side < 2; ++side) {
    const size_t si = static_cast<size_t>(side);
    const vec3 c = p.leg_contact_n[si];
    const vec3 contact = root.apply(vec3(c.x * leg, m.contact_height_m[si] + c.y * leg, c.z * leg));
    foot_rot[si] = segment_rot(kSegFootL + side);
    const int toe = m.contact[si];
    ankle[si] = toe == m.rig.leg[si].end ? contact : contact - foot_rot[si] * s.rest_offsets_m[static_cast<size_t>(toe)];
    // Lower the pelvis until a grounded foot is within reach (a short-legged character crouches a
    // little instead of floating).
    if (c.y * leg > kGroundedClearanceM) continue;
    const FighterLimb& lg = m.rig.leg[si];
    const vec3 hip = pelvis + pelvis_rot * s.rest_offsets_m[static_cast<size_t>(lg.root)];
    // Only what the leg cannot reach at all: a margin here would bend straight knees (a knee 1 mm
    // short of straight sits ~2 cm off the hip -> ankle line).
    const float reach = lg.length_m();
    const vec2 flat = ground(hip) - ground(ankle[si]);
    const float d2 = glm::dot(flat, flat);
    if (d2 >= reach * reach) continue;
    const float highest = ankle[si].y + std::sqrt(reach * reach - d2);
    if (hip.y > highest) pelvis.y -= hip.y - highest;
  }

  std::array<quat, 2> lower_rot{kIdentity, kIdentity};  // Per limb slot: 0-1 arms, filled at the upper joint.
  std::array<quat, 2> shin_rot{kIdentity, kIdentity};
  out.global_pos_m[0] = pelvis;
  out.global_rot[0] = pelvis_rot;
  out.local_pos_m[0] = pelvis;
  out.local_rot[0] = pelvis_rot;
  for (int j = 1; j < n; ++j) {
    const int parent = s.parents[static_cast<size_t>(j)];
    const vec3 offset = s.rest_offsets_m[static_cast<size_t>(j)];
    const vec3 pos = out.global_pos_m[parent] + out.global_rot[parent] * offset;
    const int idx = m.role_index[static_cast<size_t>(j)];
    const size_t si = static_cast<size_t>(idx);
    quat rot;
    switch (m.role[static_cast<size_t>(j)]) {
      case kSegment: rot = segment_rot(idx); break;
      case kSpine: rot = head * spine_frame_at(p, m.spine_u[si]) * m.spine[si].inv_frame_local; break;
      case kArmUpper: {
        const FighterLimb& arm = m.rig.arm[si];
        const vec3 target = pos + head * (p.arm_end_n[si] * m.arm_length_m[si]);
        const vec3 axis = safe_normalize(target - pos, head * vec3(0, -1, 0));
        const vec3 bend = head * swivel_direction(true, glm::inverse(head) * axis, p.arm_swivel_rad[si]);
        vec3 mid, end;
        two_bone_positions(pos, target, arm.upper_m, arm.lower_m, bend, mid, end);
        rot = frame_from_axes(mid - pos, bend) * m.arm_axes[si].inv_upper_frame_local;
        lower_rot[si] = frame_from_axes(end - mid, bend) * m.arm_axes[si].inv_lower_frame_local;
        break;
      }
      case kArmLower: rot = lower_rot[si]; break;
      case kLegUpper: {
        const FighterLimb& lg = m.rig.leg[si];
        const vec3 axis = safe_normalize(ankle[si] - pos, head * vec3(0, -1, 0));
        const vec3 bend = head * swivel_direction(false, glm::inverse(head) * axis, p.leg_swivel_rad[si]);
        vec3 mid, end;
        two_bone_positions(pos, ankle[si], lg.upper_m, lg.lower_m, bend, mid, end);
        rot = frame_from_axes(mid - pos, bend) * m.leg_axes[si].inv_upper_frame_local;
        shin_rot[si] = frame_from_axes(end - mid, bend) * m.leg_axes[si].inv_lower_frame_local;
        break;
      }
      case kLegLower: rot = shin_rot[si]; break;
      default: rot = out.global_rot[parent]; break;  // End sites and unmapped joints: rest.
    }
    rot = glm::normalize(rot);
    out.global_pos_m[j] = pos;
    out.global_rot[j] = rot;
    out.local_pos_m[j] = offset;
    out.local_rot[j] = glm::normalize(glm::inverse(out.global_rot[parent]) * rot);
  }
}

void limb_pose_blend(const LimbPose& a, const LimbPose& b, float w, LimbPose& out) {
  std::array<quat, kLimbMaxSpine> b_spine;
  for (int i = 0; i < a.num_spine; ++i) b_spine[static_cast<size_t>(i)] = spine_frame_at(b, a.spine_u[static_cast<size_t>(i)]);
  out.pelvis_n = glm::mix(a.pelvis_n, b.pelvis_n, w);
  for (size_t k = 0; k < a.frame.size(); ++k) out.frame[k] = glm::slerp(a.frame[k], b.frame[k], w);
  out.num_spine = a.num_spine;
  for (int i = 0; i < a.num_spine; ++i) {
    const size_t si = static_cast<size_t>(i);
    out.spine_frame[si] = glm::slerp(a.spine_frame[si], b_spine[si], w);
    out.spine_u[si] = a.spine_u[si];
  }
  for (size_t side = 0; side < 2; ++side) {
    out.arm_end_n[side] = glm::mix(a.arm_end_n[side], b.arm_end_n[side], w);
    out.leg_contact_n[side] = glm::mix(a.leg_contact_n[side], b.leg_contact_n[side], w);
    // Angles blend along the shorter way round.
    out.arm_swivel_rad[side] = a.arm_swivel_rad[side] + w * wrap_angle(b.arm_swivel_rad[side] - a.arm_swivel_rad[side]);
    out.leg_swivel_rad[side] = a.leg_swivel_rad[side] + w * wrap_angle(b.leg_swivel_rad[side] - a.leg_swivel_rad[side]);
  }
}

}  // namespace foresight

#include "fighter/strike_adaptation.hpp"

#include "anim/fk.hpp"
#include "anim/pose.hpp"

#include <algorithm>
#include <cmath>

namespace foresight {
namespace {

// Goals closer than this fraction of the limb's length are the limb's alone; the torso brings the
// limb root this close. Slightly under 1 so the final IK keeps a hair of bend (no popping).
constexpr float kReachFraction = 0.9995f;
constexpr float kCcdAimFraction = 0.998f;

float smoothstep01(float x) {
  x = std::clamp(x, 0.0f, 1.0f);
  return x * x * (3.0f - 2.0f * x);
}

vec3 safe_normalize(vec3 v, vec3 fallback) {
  const float l2 = glm::dot(v, v);
  return l2 > 1e-14f ? v / std::sqrt(l2) : fallback;
}

}  // namespace

bool StrikeAdapter::begin(const StrikeRequest& request, const LimbCharacter& fighter,
                          const AdaptSettings& settings, std::span<const vec3> current_local_pos_m,
                          std::span<const quat> current_local_rot, std::string& error) {
  if (!request.clip || !request.source.skeleton || !request.source.model || !fighter.skeleton || !fighter.model) {
    error = "strike adaptation: missing clip, skeleton or model";
    return false;
  }
  const Clip& clip = *request.clip;
  const int end = request.end_frame < 0 ? clip.num_frames - 1 : request.end_frame;
  if (clip.num_joints != request.source.skeleton->num_joints() || request.start_frame < 0 ||
      request.start_frame > request.hit_frame || request.hit_frame > end || end >= clip.num_frames) {
    error = "strike adaptation: frames must satisfy 0 <= start <= hit <= end < clip frames, on the clip's skeleton";
    return false;
  }
  if (request.side != kFighterLeft && request.side != kFighterRight) {
    error = "strike adaptation: side must be left (0) or right (1)";
    return false;
  }
  const int n = fighter.skeleton->num_joints();
  has_current_ = !current_local_rot.empty();
  if (has_current_ && (static_cast<int>(current_local_rot.size()) < n || static_cast<int>(current_local_pos_m.size()) < n)) {
    error = "strike adaptation: the current pose does not match the fighter's skeleton";
    return false;
  }
  req_ = request;
  fighter_ = fighter;
  settings_ = settings;
  start_ = request.start_frame;
  hit_ = request.hit_frame;
  end_ = end;
  const FighterRig& rig = fighter.model->rig;
  effector_ = request.kick ? rig.leg[static_cast<size_t>(request.side)].end : rig.arm[static_cast<size_t>(request.side)].end;
  retargeted_.resize(n);
  pose_.resize(n);
  // The current pose is encoded relative to the same root as the clip will be decoded on, so the
  // two are blended in the same (normalised) frame.
  if (has_current_)
    limb_pose_encode(*fighter.skeleton, *fighter.model, current_local_pos_m, current_local_rot, request.alignment, current_);
  retarget_frame(hit_ - start_);
  p_hit_ = retargeted_.global_pos_m[static_cast<size_t>(effector_)];
  return true;
}

int StrikeAdapter::support_contact_joint() const {
  const int support = 1 - req_.side;
  return fighter_.model->contact[static_cast<size_t>(support)];
}

void StrikeAdapter::retarget_frame(int k) {
  const Clip& clip = *req_.clip;
  const int f = start_ + k;
  LimbPose limb;
  limb_pose_encode(*req_.source.skeleton, *req_.source.model, clip.frame_pos(f), clip.frame_rot(f), Placement{}, limb);
  if (has_current_) {
    const float w = blend_out_weight(k, settings_.blend_frames);
    if (w > 0.0f) limb_pose_blend(limb, current_, w, limb);
  }
  limb_pose_decode(*fighter_.skeleton, *fighter_.model, limb, req_.alignment, retargeted_.spans());
}

void StrikeAdapter::fk() {
  fk_pose(*fighter_.skeleton, pose_.local_pos_m, pose_.local_rot, pose_.global_pos_m, pose_.global_rot);
}

// Analytic two-bone IK of one limb onto `goal`, keeping its swivel (the middle joint stays on the
// side it bends to now) and giving the end joint the global rotation `end_global_rot`.
void StrikeAdapter::solve_limb(const FighterLimb& limb, const LimbAxes& axes, vec3 goal, quat end_global_rot) {
  auto& gp = pose_.global_pos_m;
  auto& gr = pose_.global_rot;
  const vec3 root = gp[static_cast<size_t>(limb.root)], mid_now = gp[static_cast<size_t>(limb.mid)];
  const vec3 axis = safe_normalize(goal - root, vec3(0, -1, 0));
  vec3 bend = (mid_now - root) - axis * glm::dot(mid_now - root, axis);
  if (glm::dot(bend, bend) < 1e-8f) {
    bend = gr[static_cast<size_t>(limb.root)] * axes.bend_upper_local;
    bend -= axis * glm::dot(bend, axis);
  }
  bend = safe_normalize(bend, glm::abs(axis.y) < 0.9f ? glm::normalize(glm::cross(axis, vec3(0, 1, 0)))
                                                      : vec3(0, 0, 1));
  vec3 mid, end;
  two_bone_positions(root, goal, limb.upper_m, limb.lower_m, bend, mid, end);
  const quat upper = glm::normalize(frame_from_axes(mid - root, bend) * axes.inv_upper_frame_local);
  const quat lower = glm::normalize(frame_from_axes(end - mid, bend) * axes.inv_lower_frame_local);
  const int parent = fighter_.skeleton->parents[static_cast<size_t>(limb.root)];
  pose_.local_rot[static_cast<size_t>(limb.root)] = glm::normalize(glm::inverse(gr[static_cast<size_t>(parent)]) * upper);
  pose_.local_rot[static_cast<size_t>(limb.mid)] = glm::normalize(glm::inverse(upper) * lower);
  pose_.local_rot[static_cast<size_t>(limb.end)] = glm::normalize(glm::inverse(lower) * end_global_rot);
  fk();
}

// CCD over the torso until the striking limb's root is within reach of the goal. Returns the
// sweeps used.
int StrikeAdapter::solve_torso(vec3 goal) {
  const FighterRig& rig = fighter_.model->rig;
  const size_t side = static_cast<size_t>(req_.side);
  const FighterLimb& limb = req_.kick ? rig.leg[side] : rig.arm[side];
  const float reach = limb.length_m() * kReachFraction;
  auto& gp = pose_.global_pos_m;
  auto& gr = pose_.global_rot;
  std::fill(spent_rad_.begin(), spent_rad_.end(), 0.0f);
  // The chain, distal first: clavicle, chest ... first spine joint (punches); the pelvis (kicks).
  std::array<int, kLimbMaxSpine + 2> chain{};
  std::array<float, kLimbMaxSpine + 2> budget{};
  std::array<vec3, kLimbMaxSpine + 2> fixed_pivot{};  // Kicks: the pelvis turns about these.
  int num = 0;
  if (req_.kick) {
    // First the pelvis tilts about the support hip (the kicking hip rises and comes forward), then
    // the whole body leans about the support ankle (the standing leg inclines, its foot stays).
    chain[0] = 0;
    budget[0] = settings_.pelvis_budget_rad;
    chain[1] = 0;
    budget[1] = settings_.lean_budget_rad;
    fixed_pivot[1] = gp[static_cast<size_t>(rig.leg[1 - side].end)];
    num = 2;
  } else {
    if (rig.clavicle[side] > 0) {
      chain[static_cast<size_t>(num)] = rig.clavicle[side];
      budget[static_cast<size_t>(num++)] = settings_.clavicle_budget_rad;
    }
    for (int i = static_cast<int>(rig.spine.size()) - 1; i >= 0; --i) {
      if (rig.spine[static_cast<size_t>(i)] == rig.clavicle[side]) continue;
      chain[static_cast<size_t>(num)] = rig.spine[static_cast<size_t>(i)];
      budget[static_cast<size_t>(num++)] = settings_.spine_budget_rad;
    }
  }
  int sweeps = 0;
  for (; sweeps < settings_.max_ccd_iterations; ++sweeps) {
    bool moved = false;
    for (int c = 0; c < num; ++c) {
      const vec3 root = gp[static_cast<size_t>(limb.root)];
      if (glm::length(goal - root) <= reach) return sweeps + 1;
      const int j = chain[static_cast<size_t>(c)];
      const size_t ci = static_cast<size_t>(c);
      // The support hip moves when the body leans: tilt about where it is now.
      const vec3 pivot = !req_.kick ? gp[static_cast<size_t>(j)]
                         : c == 0   ? gp[static_cast<size_t>(rig.leg[1 - side].root)]
                                    : fixed_pivot[ci];
      // Turning about the pivot moves the limb root on a sphere; the smallest turn that brings it
      // within reach (slightly inside, so the next test passes) follows from the law of cosines.
      // Aiming a stand-in effector instead (textbook CCD) creeps up on the reach border: 12
      // sweeps left the child morphology 2 cm short; this needs one or two.
      const vec3 a = root - pivot, b = goal - pivot;
      const float r = glm::length(a), big_d = glm::length(b);
      if (r < 1e-5f || big_d < 1e-5f) continue;
      const vec3 axis = glm::cross(a, b);
      const float sin_len = glm::length(axis);
      if (sin_len < 1e-9f) continue;
      const float theta = std::atan2(sin_len, glm::dot(a, b));
      const float aim = reach * kCcdAimFraction;
      const float c_needed = (r * r + big_d * big_d - aim * aim) / (2.0f * r * big_d);
      float angle = c_needed >= 1.0f ? theta : theta - std::acos(std::max(-1.0f, c_needed));
      angle = std::min({angle, settings_.step_rad, budget[ci] - spent_rad_[ci]});
      if (angle <= 1e-5f) continue;
      const quat q = glm::angleAxis(angle, axis / sin_len);
      spent_rad_[ci] += angle;
      moved = true;
      if (j == 0) {  // The pelvis turns about a fixed pivot of the support leg.
        pose_.local_pos_m[0] = pivot + q * (pose_.local_pos_m[0] - pivot);
        pose_.local_rot[0] = glm::normalize(q * pose_.local_rot[0]);
      } else {
        const int parent = fighter_.skeleton->parents[static_cast<size_t>(j)];
        pose_.local_rot[static_cast<size_t>(j)] =
            glm::normalize(glm::inverse(gr[static_cast<size_t>(parent)]) * (q * gr[static_cast<size_t>(j)]));
      }
      fk();
    }
    if (!moved) break;  // Every budget spent: the goal stays out of reach.
  }
  return sweeps;
}

AdaptedFrame StrikeAdapter::pose_frame(int k) {
  k = std::clamp(k, 0, num_frames() - 1);
  retarget_frame(k);
  std::copy(retargeted_.local_pos_m.begin(), retargeted_.local_pos_m.end(), pose_.local_pos_m.begin());
  std::copy(retargeted_.local_rot.begin(), retargeted_.local_rot.end(), pose_.local_rot.begin());
  std::copy(retargeted_.global_pos_m.begin(), retargeted_.global_pos_m.end(), pose_.global_pos_m.begin());
  std::copy(retargeted_.global_rot.begin(), retargeted_.global_rot.end(), pose_.global_rot.begin());

  // d(t): 0 at the start, the full offset at the hit, 0 again at the end.
  const int kh = hit_ - start_, ke = end_ - start_;
  const float s = k <= kh ? (kh == 0 ? 1.0f : smoothstep01(static_cast<float>(k) / static_cast<float>(kh)))
                          : 1.0f - smoothstep01(static_cast<float>(k - kh) / static_cast<float>(std::max(1, ke - kh)));
  const size_t e = static_cast<size_t>(effector_);
  AdaptedFrame out;
  out.clip_frame = start_ + k;
  out.goal_m = retargeted_.global_pos_m[e] + s * (req_.target_m - p_hit_);

  const LimbModel& model = *fighter_.model;
  const size_t side = static_cast<size_t>(req_.side), support = 1 - side;
  const FighterLimb& limb = req_.kick ? model.rig.leg[side] : model.rig.arm[side];
  const LimbAxes& axes = req_.kick ? model.leg_axes[side] : model.arm_axes[side];
  const quat end_rot = retargeted_.global_rot[e];
  const float reach = limb.length_m() * kReachFraction;
  if (glm::length(out.goal_m - pose_.global_pos_m[static_cast<size_t>(limb.root)]) > reach) {
    out.ccd_iterations = solve_torso(out.goal_m);
    if (req_.kick) {  // The support leg back onto its planted foot (the hip did not move).
      const FighterLimb& sl = model.rig.leg[support];
      solve_limb(sl, model.leg_axes[support], retargeted_.global_pos_m[static_cast<size_t>(sl.end)],
                 retargeted_.global_rot[static_cast<size_t>(sl.end)]);
    }
  }
  solve_limb(limb, axes, out.goal_m, end_rot);
  out.effector_m = pose_.global_pos_m[e];
  out.reach_error_m = glm::length(out.effector_m - out.goal_m);
  out.reachable = glm::length(out.goal_m - pose_.global_pos_m[static_cast<size_t>(limb.root)]) <= limb.length_m();
  return out;
}

}  // namespace foresight

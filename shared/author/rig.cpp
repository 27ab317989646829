#include "author/rig.hpp"

#include <cmath>
#include <string>

namespace foresight::author {
namespace {

LimbRig limb(const Skeleton& s, const std::string& root, const std::string& mid,
             const std::string& end) {
  LimbRig l{s.find_joint(root), s.find_joint(mid), s.find_joint(end), 0.0f, 0.0f};
  if (l.mid >= 0) l.upper_m = glm::length(s.rest_offsets_m[l.mid]);
  if (l.end >= 0) l.lower_m = glm::length(s.rest_offsets_m[l.end]);
  return l;
}

bool points_down(const Skeleton& s, int joint) {
  if (joint < 0) return false;
  const vec3 o = s.rest_offsets_m[joint];
  return o.y < 0.0f && std::abs(o.x) < 1e-6f && std::abs(o.z) < 1e-6f;
}

}  // namespace

Rig rig_from_skeleton(const Skeleton& s) {
  Rig r;
  r.hips = s.find_joint("Hips");
  r.spine = {s.find_joint("Spine"), s.find_joint("Spine1"), s.find_joint("Chest")};
  r.neck = s.find_joint("Neck");
  r.head = s.find_joint("Head");
  r.head_top = s.find_joint("HeadTop_End");
  const char* sides[] = {"Left", "Right"};
  for (int side = 0; side < 2; ++side) {
    const std::string p = sides[side];
    r.clavicle[side] = s.find_joint(p + "Shoulder");
    r.arm[side] = limb(s, p + "Arm", p + "ForeArm", p + "Hand");
    r.hand_end[side] = s.find_joint(p + "Hand_End");
    r.leg[side] = limb(s, p + "UpLeg", p + "Leg", p + "Foot");
    r.toe[side] = s.find_joint(p + "ToeBase");
    r.toe_end[side] = s.find_joint(p + "Toe_End");
  }
  if (r.toe[kLeft] >= 0) r.ball_from_ankle_m = s.rest_offsets_m[r.toe[kLeft]];
  if (r.toe_end[kLeft] >= 0) r.toe_from_ball_m = s.rest_offsets_m[r.toe_end[kLeft]];
  // The rest pose stands on the floor, so the ankle's rest height is its flat-foot height.
  for (int j = r.leg[kLeft].end; j >= 0; j = s.parents[j]) r.ankle_height_m += s.rest_offsets_m[j].y;
  return r;
}

bool rig_valid(const Skeleton& s, const Rig& r) {
  if (r.hips != 0 || r.neck < 0 || r.head < 0 || r.head_top < 0) return false;
  for (int j : r.spine)
    if (j < 0) return false;
  for (int side = 0; side < 2; ++side) {
    for (const LimbRig* l : {&r.arm[side], &r.leg[side]})
      if (l->root < 0 || !points_down(s, l->mid) || !points_down(s, l->end)) return false;
    if (r.clavicle[side] < 0 || r.hand_end[side] < 0 || r.toe[side] < 0 || r.toe_end[side] < 0)
      return false;
  }
  return true;
}

}  // namespace foresight::author

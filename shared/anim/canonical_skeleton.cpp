#include "anim/canonical_skeleton.hpp"

#include <string>

namespace foresight {
namespace {

void add_joint(Skeleton& s, const char* name, int parent, vec3 offset_m, bool end_site) {
  s.joint_names.emplace_back(name);
  s.parents.push_back(static_cast<int16_t>(parent));
  s.rest_offsets_m.push_back(offset_m);
  s.is_end_site.push_back(end_site);
}

// Right-side joints mirror the left ones through x = 0.
void add_arm(Skeleton& s, const std::string& side, float sign, int chest) {
  const int clavicle = s.num_joints();
  add_joint(s, (side + "Shoulder").c_str(), chest, vec3(sign * 0.035f, 0.09f, 0.0f), false);
  const char* names[] = {"Arm", "ForeArm", "Hand", "Hand_End"};
  const vec3 offsets[] = {vec3(sign * 0.14f, 0, 0), vec3(0, -0.28f, 0), vec3(0, -0.26f, 0),
                          vec3(0, -0.08f, 0)};
  for (int i = 0; i < 4; ++i) add_joint(s, (side + names[i]).c_str(), clavicle + i, offsets[i], i == 3);
}

void add_leg(Skeleton& s, const std::string& side, float sign) {
  const int first = s.num_joints();
  const char* names[] = {"UpLeg", "Leg", "Foot", "ToeBase", "Toe_End"};
  const vec3 offsets[] = {vec3(sign * 0.09f, -0.05f, 0), vec3(0, -0.42f, 0), vec3(0, -0.42f, 0),
                          vec3(0, kRestBallHeightM - kRestAnkleHeightM, 0.13f), vec3(0, 0, 0.06f)};
  for (int i = 0; i < 5; ++i) add_joint(s, (side + names[i]).c_str(), i == 0 ? 0 : first + i - 1, offsets[i], i == 4);
}

}  // namespace

Skeleton canonical_skeleton() {
  Skeleton s;
  add_joint(s, "Hips", kNoParent, vec3(0, kRestPelvisHeightM, 0), false);
  add_joint(s, "Spine", 0, vec3(0, 0.10f, 0), false);
  add_joint(s, "Spine1", 1, vec3(0, 0.13f, 0), false);
  add_joint(s, "Chest", 2, vec3(0, 0.14f, 0), false);
  add_joint(s, "Neck", 3, vec3(0, 0.13f, 0), false);
  add_joint(s, "Head", 4, vec3(0, 0.11f, 0.01f), false);
  add_joint(s, "HeadTop_End", 5, vec3(0, 0.17f, 0), true);
  add_arm(s, "Left", 1.0f, kCanonChest);
  add_arm(s, "Right", -1.0f, kCanonChest);
  add_leg(s, "Left", 1.0f);
  add_leg(s, "Right", -1.0f);
  return s;
}

int canonical_primary_child(int joint) {
  switch (joint) {
    case kCanonHips: return kCanonSpine;
    case kCanonChest: return kCanonNeck;
    case kCanonHeadTop: case kCanonLeftHandEnd: case kCanonRightHandEnd:
    case kCanonLeftToeEnd: case kCanonRightToeEnd: return -1;
    default: return joint + 1;  // every other joint's bone runs to the next joint in the order
  }
}

}  // namespace foresight

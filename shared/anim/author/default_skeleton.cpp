#include "anim/author/default_skeleton.hpp"

#include <string>

namespace foresight::author {
namespace {

struct JointDef {
  const char* name;
  int parent;
  vec3 offset_m;
  bool end_site;
};

// Proportions of a 1.75 m adult: leg 0.84 m hip to ankle (thigh = shin so the knee sits halfway),
// arm 0.54 m shoulder to wrist, shoulder joints 0.35 m apart at 1.43 m. Depth-first order, so every
// parent precedes its children; right-side joints mirror the left ones through x = 0.
void add_joint(Skeleton& s, const JointDef& d) {
  s.joint_names.emplace_back(d.name);
  s.parents.push_back(static_cast<int16_t>(d.parent));
  s.rest_offsets_m.push_back(d.offset_m);
  s.is_end_site.push_back(d.end_site);
}

void add_arm(Skeleton& s, const std::string& side, float sign, int chest) {
  const int clavicle = s.num_joints();
  s.joint_names.push_back(side + "Shoulder");
  s.parents.push_back(static_cast<int16_t>(chest));
  s.rest_offsets_m.push_back(vec3(sign * 0.035f, 0.09f, 0.0f));
  s.is_end_site.push_back(false);
  const char* names[] = {"Arm", "ForeArm", "Hand", "Hand_End"};
  const vec3 offsets[] = {vec3(sign * 0.14f, 0, 0), vec3(0, -0.28f, 0), vec3(0, -0.26f, 0),
                          vec3(0, -0.08f, 0)};
  for (int i = 0; i < 4; ++i) {
    s.joint_names.push_back(side + names[i]);
    s.parents.push_back(static_cast<int16_t>(clavicle + i));
    s.rest_offsets_m.push_back(offsets[i]);
    s.is_end_site.push_back(i == 3);
  }
}

void add_leg(Skeleton& s, const std::string& side, float sign) {
  const int first = s.num_joints();
  const char* names[] = {"UpLeg", "Leg", "Foot", "ToeBase", "Toe_End"};
  const vec3 offsets[] = {vec3(sign * 0.09f, -0.05f, 0), vec3(0, -0.42f, 0), vec3(0, -0.42f, 0),
                          vec3(0, kRestBallHeightM - kRestAnkleHeightM, 0.13f), vec3(0, 0, 0.06f)};
  for (int i = 0; i < 5; ++i) {
    s.joint_names.push_back(side + names[i]);
    s.parents.push_back(static_cast<int16_t>(i == 0 ? 0 : first + i - 1));
    s.rest_offsets_m.push_back(offsets[i]);
    s.is_end_site.push_back(i == 4);
  }
}

}  // namespace

Skeleton default_skeleton() {
  Skeleton s;
  add_joint(s, {"Hips", kNoParent, vec3(0, kRestPelvisHeightM, 0), false});
  add_joint(s, {"Spine", 0, vec3(0, 0.10f, 0), false});
  add_joint(s, {"Spine1", 1, vec3(0, 0.13f, 0), false});
  add_joint(s, {"Chest", 2, vec3(0, 0.14f, 0), false});
  add_joint(s, {"Neck", 3, vec3(0, 0.13f, 0), false});
  add_joint(s, {"Head", 4, vec3(0, 0.11f, 0.01f), false});
  add_joint(s, {"HeadTop_End", 5, vec3(0, 0.17f, 0), true});
  add_arm(s, "Left", 1.0f, 3);
  add_arm(s, "Right", -1.0f, 3);
  add_leg(s, "Left", 1.0f);
  add_leg(s, "Right", -1.0f);
  return s;
}

}  // namespace foresight::author

#include "fighter/fighter_rig.hpp"

#include <algorithm>
#include <cctype>
#include <initializer_list>
#include <string_view>

namespace foresight {
namespace {

bool same_name(std::string_view a, std::string_view b) {
  return a.size() == b.size() &&
         std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

// The first joint whose name is one of `names` ("{L}"/"{R}" side placeholders already expanded).
int find_any(const Skeleton& s, std::initializer_list<std::string> names) {
  for (const std::string& n : names)
    for (int j = 0; j < s.num_joints(); ++j)
      if (!s.is_end_site[static_cast<size_t>(j)] && same_name(s.joint_names[static_cast<size_t>(j)], n)) return j;
  return -1;
}

float bone_length(const Skeleton& s, int joint) { return glm::length(s.rest_offsets_m[static_cast<size_t>(joint)]); }

FighterLimb limb(const Skeleton& s, int root, int mid, int end) {
  FighterLimb l{root, mid, end, 0.0f, 0.0f};
  if (root >= 0 && mid >= 0 && end >= 0) {
    l.upper_m = bone_length(s, mid);
    l.lower_m = bone_length(s, end);
  }
  return l;
}

// True when `ancestor` is on the parent chain of `joint`.
bool descends_from(const Skeleton& s, int joint, int ancestor) {
  for (int j = joint; j >= 0; j = s.parents[static_cast<size_t>(j)])
    if (j == ancestor) return true;
  return false;
}

}  // namespace

bool fighter_rig_from_skeleton(const Skeleton& s, FighterRig& rig, std::string& error) {
  rig = FighterRig{};
  if (!s.valid() || s.num_joints() == 0) {
    error = "fighter rig: the skeleton is not valid";
    return false;
  }
  rig.pelvis = 0;
  rig.neck = find_any(s, {"Neck", "Neck1"});
  rig.head = find_any(s, {"Head"});
  const char* side_word[] = {"Left", "Right"};
  const char* side_tag[] = {"L", "R"};
  for (int side = 0; side < 2; ++side) {
    const std::string w = side_word[side], t = side_tag[side];
    const int shoulder = find_any(s, {w + "Arm", "UpperArm_" + t, w + "UpperArm"});
    const int elbow = find_any(s, {w + "ForeArm", "LowerArm_" + t, w + "LowerArm"});
    const int wrist = find_any(s, {w + "Hand", "Hand_" + t});
    const int hip = find_any(s, {w + "UpLeg", "UpperLeg_" + t, w + "UpperLeg", w + "Thigh"});
    const int knee = find_any(s, {w + "Leg", "LowerLeg_" + t, w + "LowerLeg", w + "Shin"});
    const int ankle = find_any(s, {w + "Foot", "Foot_" + t});
    rig.arm[static_cast<size_t>(side)] = limb(s, shoulder, elbow, wrist);
    rig.leg[static_cast<size_t>(side)] = limb(s, hip, knee, ankle);
    rig.toe[static_cast<size_t>(side)] = find_any(s, {w + "ToeBase", "Toes_" + t, w + "Toe"});
    rig.clavicle[static_cast<size_t>(side)] = shoulder >= 0 ? s.parents[static_cast<size_t>(shoulder)] : -1;
  }

  auto missing = [&](const char* role) {
    error = std::string("fighter rig: no joint for the ") + role + " (see shared/fighter/fighter_rig.cpp for the names)";
    return false;
  };
  if (rig.neck < 0) return missing("neck");
  if (rig.head < 0 || !descends_from(s, rig.head, rig.neck)) return missing("head (below the neck)");
  for (int side = 0; side < 2; ++side) {
    const FighterLimb& a = rig.arm[static_cast<size_t>(side)];
    const FighterLimb& l = rig.leg[static_cast<size_t>(side)];
    if (a.root < 0 || a.mid < 0 || a.end < 0 || s.parents[static_cast<size_t>(a.end)] != a.mid ||
        s.parents[static_cast<size_t>(a.mid)] != a.root)
      return missing(side == 0 ? "left arm (shoulder, elbow, wrist in a chain)" : "right arm (shoulder, elbow, wrist in a chain)");
    if (l.root < 0 || l.mid < 0 || l.end < 0 || s.parents[static_cast<size_t>(l.end)] != l.mid ||
        s.parents[static_cast<size_t>(l.mid)] != l.root)
      return missing(side == 0 ? "left leg (hip, knee, ankle in a chain)" : "right leg (hip, knee, ankle in a chain)");
  }
  // The spine: the neck's ancestors up to (not including) the pelvis, pelvis side first.
  for (int j = s.parents[static_cast<size_t>(rig.neck)]; j > 0; j = s.parents[static_cast<size_t>(j)])
    rig.spine.push_back(j);
  std::reverse(rig.spine.begin(), rig.spine.end());
  if (rig.spine.empty()) return missing("spine (joints between the pelvis and the neck)");

  float trunk = 0.0f;
  for (int j = rig.head; j > 0; j = s.parents[static_cast<size_t>(j)]) trunk += bone_length(s, j);
  rig.body_size_m = trunk + 0.5f * (rig.leg[0].length_m() + rig.leg[1].length_m());
  if (!(rig.body_size_m > 0.0f)) {
    error = "fighter rig: zero bone lengths";
    return false;
  }
  return true;
}

}  // namespace foresight

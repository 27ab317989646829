#include "fighter/morphology.hpp"

#include "author/default_skeleton.hpp"

#include <algorithm>
#include <cassert>
#include <string_view>

namespace foresight {
namespace {

enum class BoneGroup { kRoot, kLegs, kArms, kSpine, kNeckHead, kWidth };

bool ends_with(std::string_view s, std::string_view tail) {
  return s.size() >= tail.size() && s.substr(s.size() - tail.size()) == tail;
}

// The group of the bone that ends at `joint` (its rest offset), by the default skeleton's names.
BoneGroup group_of(std::string_view name) {
  if (name == "Hips") return BoneGroup::kRoot;
  if (ends_with(name, "UpLeg") || (ends_with(name, "Arm") && !ends_with(name, "ForeArm")))
    return BoneGroup::kWidth;
  if (ends_with(name, "Leg") || ends_with(name, "Foot") || ends_with(name, "ToeBase") ||
      ends_with(name, "Toe_End"))
    return BoneGroup::kLegs;
  if (ends_with(name, "ForeArm") || ends_with(name, "Hand") || ends_with(name, "Hand_End"))
    return BoneGroup::kArms;
  if (name == "Head" || name == "HeadTop_End") return BoneGroup::kNeckHead;
  return BoneGroup::kSpine;  // Spine, Spine1, Chest, Neck, {Left,Right}Shoulder
}

float factor(const MorphologyScales& s, BoneGroup g) {
  switch (g) {
    case BoneGroup::kLegs: return s.legs;
    case BoneGroup::kArms: return s.arms;
    case BoneGroup::kSpine: return s.spine;
    case BoneGroup::kNeckHead: return s.neck_head;
    case BoneGroup::kWidth: return s.width;
    case BoneGroup::kRoot: break;
  }
  return 1.0f;
}

constexpr std::array<MorphologySpec, kNumMorphologies> kSpecs{{
    {"stocky", {0.76f, 0.92f, 1.05f, 1.00f, 1.30f}},
    {"tall", {1.22f, 1.08f, 1.05f, 1.00f, 0.95f}},
    {"long_arms", {1.00f, 1.30f, 1.00f, 1.00f, 1.05f}},
    {"child", {0.62f, 0.62f, 0.66f, 0.95f, 0.72f}},
    {"heavy_torso", {0.90f, 0.95f, 1.25f, 1.05f, 1.30f}},
}};

Morphology finish(std::string name, const MorphologyScales& scales) {
  Morphology m;
  m.name = std::move(name);
  m.scales = scales;
  m.skeleton = scale_default_skeleton(scales);
  std::string error;
  [[maybe_unused]] const bool ok = fighter_rig_from_skeleton(m.skeleton, m.rig, error);
  assert(ok && "the default skeleton's names always give a rig");
  m.ankle_height_m = author::kRestAnkleHeightM * scales.legs;
  m.ball_height_m = author::kRestBallHeightM * scales.legs;
  // Rest pose: every global rotation is the identity, so heights are sums of offsets.
  const Skeleton& s = m.skeleton;
  std::vector<float> y(static_cast<size_t>(s.num_joints()));
  float top = 0.0f;
  for (int j = 0; j < s.num_joints(); ++j) {
    const int p = s.parents[static_cast<size_t>(j)];
    y[static_cast<size_t>(j)] = (p < 0 ? 0.0f : y[static_cast<size_t>(p)]) + s.rest_offsets_m[static_cast<size_t>(j)].y;
    top = std::max(top, y[static_cast<size_t>(j)]);
  }
  m.height_m = top;
  return m;
}

}  // namespace

const std::array<MorphologySpec, kNumMorphologies>& morphology_specs() { return kSpecs; }

Skeleton scale_default_skeleton(const MorphologyScales& scales) {
  assert(scales.legs > 0 && scales.arms > 0 && scales.spine > 0 && scales.neck_head > 0 && scales.width > 0);
  Skeleton s = author::default_skeleton();
  for (int j = 1; j < s.num_joints(); ++j)
    s.rest_offsets_m[static_cast<size_t>(j)] *= factor(scales, group_of(s.joint_names[static_cast<size_t>(j)]));
  // Stand the rest pose on the floor: the pelvis sits above the ankle by the (scaled) leg chain,
  // and the ankle sits ankle-height above the sole.
  const int hip = s.find_joint("LeftUpLeg"), knee = s.find_joint("LeftLeg"), ankle = s.find_joint("LeftFoot");
  assert(hip > 0 && knee > 0 && ankle > 0);
  const float drop = -(s.rest_offsets_m[static_cast<size_t>(hip)].y + s.rest_offsets_m[static_cast<size_t>(knee)].y +
                       s.rest_offsets_m[static_cast<size_t>(ankle)].y);
  s.rest_offsets_m[0] = vec3(0.0f, drop + author::kRestAnkleHeightM * scales.legs, 0.0f);
  return s;
}

Morphology make_morphology(const MorphologySpec& spec) { return finish(spec.name, spec.scales); }

std::vector<Morphology> default_morphologies() {
  std::vector<Morphology> v;
  v.reserve(kSpecs.size());
  for (const MorphologySpec& spec : kSpecs) v.push_back(make_morphology(spec));
  return v;
}

Morphology default_morphology() { return finish("default", MorphologyScales{}); }

}  // namespace foresight

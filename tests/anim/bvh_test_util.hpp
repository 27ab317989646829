#pragma once
// Helpers shared by the BVH tests: a small humanoid built in code, and FK of an imported clip.
#include "import/bvh.hpp"
#include "import/bvh_import.hpp"
#include "anim/fk.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace foresight::test {

/// Y-up (x, y, z) written in a Z-up file: (x, -z, y) (the inverse of the importer's Z-up fix).
inline vec3 y_up_to_z_up(vec3 v) { return {v.x, -v.z, v.y}; }

/// A 21-joint humanoid standing at the origin (metres, Y up, faces +Z, arms down), 3 frames:
/// frame 1 turns it 30 degrees about up and steps 0.5 m forward, frame 2 bends the left elbow.
/// `scale` converts metres to the file unit; `z_up` writes the same motion in Z-up axes.
/// Hips carries "Xposition Yposition Zposition Zrotation Xrotation Yrotation"; the other joints
/// "Zrotation Xrotation Yrotation".
inline BvhDocument humanoid_document(float scale, bool z_up) {
  struct Def {
    const char* name;
    int parent;
    vec3 offset;
  };
  // clang-format off
  const Def defs[] = {
      {"Hips", -1, {0, 0.9f, 0}},
      {"Spine", 0, {0, 0.1f, 0}},        {"Chest", 1, {0, 0.2f, 0}},
      {"Neck", 2, {0, 0.2f, 0}},         {"Head", 3, {0, 0.1f, 0}},
      {"Head_End", 4, {0, 0.15f, 0}},
      {"LeftArm", 2, {0.2f, 0.15f, 0}},  {"LeftForeArm", 6, {0, -0.3f, 0}},
      {"LeftHand", 7, {0, -0.25f, 0}},   {"LeftHand_End", 8, {0, -0.1f, 0}},
      {"RightArm", 2, {-0.2f, 0.15f, 0}}, {"RightForeArm", 10, {0, -0.3f, 0}},
      {"RightHand", 11, {0, -0.25f, 0}}, {"RightHand_End", 12, {0, -0.1f, 0}},
      {"LeftUpLeg", 0, {0.1f, 0, 0}},    {"LeftLeg", 14, {0, -0.42f, 0}},
      {"LeftFoot", 15, {0, -0.4f, 0}},   {"LeftToe", 16, {0, -0.03f, 0.12f}},
      {"RightUpLeg", 0, {-0.1f, 0, 0}},  {"RightLeg", 18, {0, -0.42f, 0}},
      {"RightFoot", 19, {0, -0.4f, 0}},
  };
  // clang-format on
  using C = BvhChannel;
  BvhDocument doc;
  for (const Def& d : defs) {
    BvhJoint j;
    j.name = d.name;
    j.parent = d.parent;
    j.offset = (z_up ? y_up_to_z_up(d.offset) : d.offset) * scale;
    j.end_site = std::string(d.name).ends_with("_End");
    if (!j.end_site) j.channels = {C::kZrotation, C::kXrotation, C::kYrotation};
    if (d.parent < 0)
      j.channels.insert(j.channels.begin(), {C::kXposition, C::kYposition, C::kZposition});
    doc.joints.push_back(j);
  }
  doc.num_frames = 3;
  doc.frame_time_s = 1.0 / 30.0;
  const int nc = doc.num_channels();
  doc.values.assign(static_cast<size_t>(nc) * 3, 0.0f);
  for (int f = 0; f < 3; ++f) {
    float* v = doc.values.data() + static_cast<size_t>(f) * nc;
    const vec3 hips = (z_up ? y_up_to_z_up(vec3(0, 0.9f, 0.5f * (f > 0))) : vec3(0, 0.9f, 0.5f * (f > 0))) * scale;
    v[0] = hips.x, v[1] = hips.y, v[2] = hips.z;
    // A turn about "up": Yrotation in a Y-up file, Zrotation in a Z-up one.
    if (f > 0) (z_up ? v[3] : v[5]) = 30.0f;
    if (f == 2) v[doc.channel_offset(7) + 1] = -70.0f;  // LeftForeArm: Xrotation
  }
  return doc;
}

/// Clip-space joint positions of every frame of an imported clip.
inline std::vector<vec3> clip_positions(const Skeleton& skeleton, const Clip& clip) {
  std::vector<vec3> out;
  fk_clip_positions(skeleton, clip, out);
  return out;
}

inline void expect_near_positions(const std::vector<vec3>& a, const std::vector<vec3>& b,
                                  float tolerance) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i)
    EXPECT_LT(glm::length(a[i] - b[i]), tolerance) << "entry " << i;
}

}  // namespace foresight::test

#pragma once
// BVH documents rewritten in code the ways other exporters write the same motion: another unit,
// an extra parent joint (a dummy root, a twist bone), other Euler orders, a higher frame rate,
// fingers. Tests build capture variants from the Bandai takes with these (never copies on disk
// in the repository: the takes' licence keeps them in ../shared/mocap).
#include "import/bvh.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtx/euler_angles.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace foresight::test {

inline void scale_document(BvhDocument& doc, float k) {
  for (BvhJoint& j : doc.joints) j.offset *= k;
  const int nc = doc.num_channels();
  for (int f = 0; f < doc.num_frames; ++f)
    for (size_t j = 0; j < doc.joints.size(); ++j) {
      float* v = doc.values.data() + static_cast<size_t>(f) * nc + doc.channel_offset(static_cast<int>(j));
      for (size_t c = 0; c < doc.joints[j].channels.size(); ++c)
        if (bvh_channel_is_position(doc.joints[j].channels[c])) v[c] *= k;
    }
}

// Inserts a joint between `joint` and its parent, `fraction` of the way along the bone, with
// zero rotation channels (a twist bone, or a dummy root when `joint` is the ROOT).
inline void insert_parent(BvhDocument& doc, int joint, const std::string& name, float fraction) {
  using C = BvhChannel;
  BvhJoint extra;
  extra.name = name;
  extra.parent = doc.joints[static_cast<size_t>(joint)].parent;
  extra.offset = doc.joints[static_cast<size_t>(joint)].offset * fraction;
  extra.channels = {C::kXposition, C::kYposition, C::kZposition, C::kZrotation, C::kXrotation, C::kYrotation};
  const int nc_old = doc.num_channels();
  std::vector<BvhJoint> joints;
  for (size_t j = 0; j < doc.joints.size(); ++j) {
    if (static_cast<int>(j) == joint) joints.push_back(extra);
    BvhJoint copy = doc.joints[j];
    if (copy.parent >= joint) ++copy.parent;
    if (static_cast<int>(j) == joint) {
      copy.parent = joint;
      copy.offset -= extra.offset;
    }
    joints.push_back(copy);
  }
  std::vector<float> values;
  const int insert_at = doc.channel_offset(joint);
  for (int f = 0; f < doc.num_frames; ++f) {
    const float* v = doc.values.data() + static_cast<size_t>(f) * nc_old;
    values.insert(values.end(), v, v + insert_at);
    values.insert(values.end(), {extra.offset.x, extra.offset.y, extra.offset.z, 0.0f, 0.0f, 0.0f});
    values.insert(values.end(), v + insert_at, v + nc_old);
  }
  // The moved joint's position channels (which replace its OFFSET) lose the same part.
  doc.joints = joints;
  doc.values = values;
  const int nc = doc.num_channels();
  const BvhJoint& moved = doc.joints[static_cast<size_t>(joint) + 1];
  if (moved.parent >= 0 && moved.channels.size() == 6)
    for (int f = 0; f < doc.num_frames; ++f) {
      float* v = doc.values.data() + static_cast<size_t>(f) * nc + doc.channel_offset(joint + 1);
      for (int a = 0; a < 3; ++a) v[a] -= extra.offset[a];
    }
}

inline int joint_named(const BvhDocument& doc, const std::string& name) {
  for (size_t j = 0; j < doc.joints.size(); ++j)
    if (doc.joints[j].name == name) return static_cast<int>(j);
  ADD_FAILURE() << "no joint " << name;
  return 0;
}

// Rewrites every joint's rotation channels in `order` (e.g. "XYZ": R = Rx Ry Rz), same rotations.
inline void reorder_rotations(BvhDocument& doc, const std::string& order) {
  using C = BvhChannel;
  const int nc = doc.num_channels();
  const C axis_channel[3] = {C::kXrotation, C::kYrotation, C::kZrotation};
  for (int f = 0; f < doc.num_frames; ++f)
    for (size_t j = 0; j < doc.joints.size(); ++j) {
      BvhJoint& joint = doc.joints[j];
      float* v = doc.values.data() + static_cast<size_t>(f) * nc + doc.channel_offset(static_cast<int>(j));
      glm::dmat4 r(1.0);
      int first_rotation = -1;
      for (size_t c = 0; c < joint.channels.size(); ++c) {
        if (bvh_channel_is_position(joint.channels[c])) continue;
        if (first_rotation < 0) first_rotation = static_cast<int>(c);
        glm::dvec3 axis(0.0);
        axis[bvh_channel_axis(joint.channels[c])] = 1.0;
        r = r * glm::rotate(glm::dmat4(1.0), glm::radians(static_cast<double>(v[c])), axis);
      }
      if (first_rotation < 0) continue;
      double a = 0, b = 0, c = 0;
      if (order == "XYZ") glm::extractEulerAngleXYZ(r, a, b, c);
      else if (order == "YXZ") glm::extractEulerAngleYXZ(r, a, b, c);
      else glm::extractEulerAngleZYX(r, a, b, c);
      const double angles[3] = {a, b, c};
      for (int k = 0; k < 3; ++k) v[first_rotation + k] = static_cast<float>(glm::degrees(angles[k]));
    }
  for (BvhJoint& joint : doc.joints) {
    auto it = std::find_if(joint.channels.begin(), joint.channels.end(),
                           [](C c) { return !bvh_channel_is_position(c); });
    if (it == joint.channels.end()) continue;
    for (int k = 0; k < 3; ++k) *(it + k) = axis_channel[order[static_cast<size_t>(k)] - 'X'];
  }
}

// The body turned `deg` about the vertical on its own path (the pelvis joint's rotation turned, its
// positions kept): a walk forwards becomes a crab walk sideways, its feet sliding. Rotation
// channels are rewritten in ZYX order. Y is up.
inline void turn_body_on_its_path(BvhDocument& doc, int pelvis, double deg) {
  reorder_rotations(doc, "ZYX");
  const int nc = doc.num_channels();
  const BvhJoint& joint = doc.joints[static_cast<size_t>(pelvis)];
  int first_rotation = -1;
  for (size_t c = 0; c < joint.channels.size() && first_rotation < 0; ++c)
    if (!bvh_channel_is_position(joint.channels[c])) first_rotation = static_cast<int>(c);
  if (first_rotation < 0) return;
  const glm::dmat4 yaw = glm::rotate(glm::dmat4(1.0), glm::radians(deg), glm::dvec3(0.0, 1.0, 0.0));
  for (int f = 0; f < doc.num_frames; ++f) {
    float* v = doc.values.data() + static_cast<size_t>(f) * nc + doc.channel_offset(pelvis) + first_rotation;
    glm::dmat4 r = yaw;
    for (int k = 0; k < 3; ++k) {
      glm::dvec3 axis(0.0);
      axis[2 - k] = 1.0;  // Z, Y, X
      r = r * glm::rotate(glm::dmat4(1.0), glm::radians(static_cast<double>(v[k])), axis);
    }
    double a = 0, b = 0, c = 0;
    glm::extractEulerAngleZYX(r, a, b, c);
    v[0] = static_cast<float>(glm::degrees(a));
    v[1] = static_cast<float>(glm::degrees(b));
    v[2] = static_cast<float>(glm::degrees(c));
  }
}

// Frames linearly interpolated in between: the take at `factor` times its rate.
inline void upsample(BvhDocument& doc, int factor) {
  const int nc = doc.num_channels();
  std::vector<float> values;
  for (int f = 0; f + 1 < doc.num_frames; ++f)
    for (int k = 0; k < factor; ++k)
      for (int c = 0; c < nc; ++c) {
        const float a = doc.values[static_cast<size_t>(f) * nc + c], b = doc.values[static_cast<size_t>(f + 1) * nc + c];
        // Angles wrap: interpolate the short way.
        const float d = std::remainder(b - a, 360.0f);
        values.push_back(a + (std::fabs(b - a) > 180.0f ? d : b - a) * static_cast<float>(k) / factor);
      }
  values.insert(values.end(), doc.values.end() - nc, doc.values.end());
  doc.values = values;
  doc.num_frames = (doc.num_frames - 1) * factor + 1;
  doc.frame_time_s /= factor;
}

// Five three-joint fingers on `hand` (its local X runs along the hand, as in the Bandai rig;
// `sign` -1 for a right hand), each curled a little more than the last.
inline void add_fingers(BvhDocument& doc, const std::string& hand, float sign) {
  using C = BvhChannel;
  for (int finger = 0; finger < 5; ++finger) {
    int parent = joint_named(doc, hand);
    for (int k = 0; k < 3; ++k) {
      BvhJoint j;
      j.name = hand + "Finger" + std::to_string(finger) + "_" + std::to_string(k);
      j.parent = parent;
      j.offset = k == 0 ? vec3(sign * 8.0f, 0.0f, (finger - 2) * 2.0f) : vec3(sign * 3.0f, 0.0f, 0.0f);
      j.channels = {C::kZrotation, C::kXrotation, C::kYrotation};
      // Inserted after the parent's subtree so far (depth-first order stays).
      auto inside = [&](int x) {
        for (int p = x; p >= 0; p = doc.joints[static_cast<size_t>(p)].parent)
          if (p == parent) return true;
        return false;
      };
      int at = parent + 1;
      while (at < static_cast<int>(doc.joints.size()) && inside(at)) ++at;
      const int nc_old = doc.num_channels();
      const int value_at = at < static_cast<int>(doc.joints.size()) ? doc.channel_offset(at) : nc_old;
      for (BvhJoint& other : doc.joints)
        if (other.parent >= at) ++other.parent;
      doc.joints.insert(doc.joints.begin() + at, j);
      std::vector<float> values;
      for (int f = 0; f < doc.num_frames; ++f) {
        const float* v = doc.values.data() + static_cast<size_t>(f) * nc_old;
        values.insert(values.end(), v, v + value_at);
        values.insert(values.end(), {10.0f * static_cast<float>(finger), 0.0f, 0.0f});
        values.insert(values.end(), v + value_at, v + nc_old);
      }
      doc.values = values;
      parent = at;
    }
  }
}

}  // namespace foresight::test

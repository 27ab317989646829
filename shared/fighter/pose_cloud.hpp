#pragma once
// The pose distance of the fighter database (paper 3.2.2): a pose is a cloud of 15 key points
// (pelvis, chest, head, shoulders, elbows, wrists, hips, knees, ankles) in the pose's root frame
// divided by the actor's body size, so actors and characters of different sizes compare; two
// clouds are compared after the rotation about Y and the ground translation that bring them
// closest (Kovar and Gleicher's aligned point-cloud distance), found in closed form.
//
// Hot-path layout: a cloud is 45 floats, x[15] then y[15] then z[15], with x and z centred on the
// cloud's ground centroid (centring is free to do once and removes the translation from the
// inner loop). For centred clouds a and b:
//   C = sum(ax bx + az bz),  S = sum(ax bz - az bx),  r = sqrt(C^2 + S^2)
//   min over heading h of sum |a - R(h) b|^2 = |a_xz|^2 + |b_xz|^2 - 2 r + sum (ay - by)^2
// with cos h = C / r, sin h = S / r (R as rotate_ground in math/types.hpp).
#include "fighter/fighter_rig.hpp"
#include "math/types.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <span>

#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#define FORESIGHT_POSE_CLOUD_SSE2 1
#endif

namespace foresight {

inline constexpr int kPoseKeyPoints = 15;
inline constexpr int kPoseCloudFloats = 3 * kPoseKeyPoints;

/// The key-point joints of a rig, in the fixed order above (left side before right).
std::array<int, kPoseKeyPoints> fighter_key_joints(const FighterRig& rig);

/// Key points of one pose, metres, in the root frame `root` (root.inverse() applied to the model-
/// space joint positions `global_pos_m`, one per skeleton joint).
void fighter_key_points_m(const FighterRig& rig, std::span<const vec3> global_pos_m, const Placement& root,
                          std::span<vec3, kPoseKeyPoints> out);

/// A cloud in the hot-path layout.
struct PoseCloud {
  std::array<float, kPoseCloudFloats> pts{};  ///< x[15], y[15], z[15]; x, z centred.
  float sum_sq_xz = 0.0f;                     ///< sum(x^2 + z^2) of the centred points.
  vec2 centroid_xz{0.0f};                     ///< What was removed from x and z.
};

/// Centres `points` (already divided by the body size) into `out`.
void pose_cloud_from_points(std::span<const vec3, kPoseKeyPoints> points, PoseCloud& out);
/// Same, writing the 45 floats to `pts` (a row of a structure-of-arrays table).
void pose_cloud_pack(std::span<const vec3, kPoseKeyPoints> points, float* pts, float& sum_sq_xz, vec2& centroid_xz);

/// Squared aligned distance between centred clouds; C and S as above (to build the alignment).
inline float pose_cloud_distance_sq(const float* a, float a_ss, const float* b, float b_ss, float& c_out,
                                    float& s_out) {
  const float* ax = a;
  const float* ay = a + kPoseKeyPoints;
  const float* az = a + 2 * kPoseKeyPoints;
  const float* bx = b;
  const float* by = b + kPoseKeyPoints;
  const float* bz = b + 2 * kPoseKeyPoints;
  // Four independent lanes (points i, i+4, i+8; then the last three) so the compiler can keep
  // them in one SIMD register each: a single running sum is a serial dependency chain, and
  // without -ffast-math the compiler may not reorder it.
  float cl[4] = {0, 0, 0, 0}, sl[4] = {0, 0, 0, 0}, yl[4] = {0, 0, 0, 0};
  for (int i = 0; i + 4 <= kPoseKeyPoints; i += 4)
    for (int l = 0; l < 4; ++l) {
      cl[l] += ax[i + l] * bx[i + l] + az[i + l] * bz[i + l];
      sl[l] += ax[i + l] * bz[i + l] - az[i + l] * bx[i + l];
      const float dy = ay[i + l] - by[i + l];
      yl[l] += dy * dy;
    }
  for (int i = kPoseKeyPoints / 4 * 4, l = 0; i < kPoseKeyPoints; ++i, ++l) {
    cl[l] += ax[i] * bx[i] + az[i] * bz[i];
    sl[l] += ax[i] * bz[i] - az[i] * bx[i];
    const float dy = ay[i] - by[i];
    yl[l] += dy * dy;
  }
  const float c = (cl[0] + cl[1]) + (cl[2] + cl[3]);
  const float s = (sl[0] + sl[1]) + (sl[2] + sl[3]);
  const float y = (yl[0] + yl[1]) + (yl[2] + yl[3]);
  c_out = c;
  s_out = s;
  // Rounding can take a perfect match a hair below zero.
  return std::max(0.0f, a_ss + b_ss - 2.0f * std::sqrt(c * c + s * s) + y);
}

/// The retrieval index's layout: the cloud padded to 16 points (x[16], y[16], z[16], point 15 of
/// each zero), so the distance is exactly four 4-wide lanes with no remainder.
inline constexpr int kPoseLanePoints = 16;
inline constexpr int kPoseCloudPaddedFloats = 3 * kPoseLanePoints;

/// Copies a 45-float cloud into the padded 48-float layout (pads zero).
inline void pose_cloud_pad(const float* pts, float* padded) {
  for (int axis = 0; axis < 3; ++axis) {
    for (int i = 0; i < kPoseKeyPoints; ++i) padded[axis * kPoseLanePoints + i] = pts[axis * kPoseKeyPoints + i];
    for (int i = kPoseKeyPoints; i < kPoseLanePoints; ++i) padded[axis * kPoseLanePoints + i] = 0.0f;
  }
}

/// pose_cloud_distance_sq on padded clouds. The lanes hold the same points in the same order as
/// the 45-float version (the pad adds +0 to lane 3), so the result is the same to the bit; with
/// SSE2 it is twelve 4-wide loads per cloud and no scalar remainder.
inline float pose_cloud_distance_sq_padded(const float* a, float a_ss, const float* b, float b_ss, float& c_out,
                                           float& s_out) {
  float c, s, y;
#if defined(FORESIGHT_POSE_CLOUD_SSE2)
  __m128 cl = _mm_setzero_ps(), sl = _mm_setzero_ps(), yl = _mm_setzero_ps();
  for (int i = 0; i < kPoseLanePoints; i += 4) {
    const __m128 ax = _mm_loadu_ps(a + i), ay = _mm_loadu_ps(a + kPoseLanePoints + i),
                 az = _mm_loadu_ps(a + 2 * kPoseLanePoints + i);
    const __m128 bx = _mm_loadu_ps(b + i), by = _mm_loadu_ps(b + kPoseLanePoints + i),
                 bz = _mm_loadu_ps(b + 2 * kPoseLanePoints + i);
    cl = _mm_add_ps(cl, _mm_add_ps(_mm_mul_ps(ax, bx), _mm_mul_ps(az, bz)));
    sl = _mm_add_ps(sl, _mm_sub_ps(_mm_mul_ps(ax, bz), _mm_mul_ps(az, bx)));
    const __m128 dy = _mm_sub_ps(ay, by);
    yl = _mm_add_ps(yl, _mm_mul_ps(dy, dy));
  }
  alignas(16) float cv[4], sv[4], yv[4];
  _mm_store_ps(cv, cl);
  _mm_store_ps(sv, sl);
  _mm_store_ps(yv, yl);
  c = (cv[0] + cv[1]) + (cv[2] + cv[3]);
  s = (sv[0] + sv[1]) + (sv[2] + sv[3]);
  y = (yv[0] + yv[1]) + (yv[2] + yv[3]);
#else
  float cl[4] = {0, 0, 0, 0}, sl[4] = {0, 0, 0, 0}, yl[4] = {0, 0, 0, 0};
  for (int i = 0; i < kPoseLanePoints; i += 4)
    for (int l = 0; l < 4; ++l) {
      const float ax = a[i + l], ay = a[kPoseLanePoints + i + l], az = a[2 * kPoseLanePoints + i + l];
      const float bx = b[i + l], by = b[kPoseLanePoints + i + l], bz = b[2 * kPoseLanePoints + i + l];
      cl[l] += ax * bx + az * bz;
      sl[l] += ax * bz - az * bx;
      const float dy = ay - by;
      yl[l] += dy * dy;
    }
  c = (cl[0] + cl[1]) + (cl[2] + cl[3]);
  s = (sl[0] + sl[1]) + (sl[2] + sl[3]);
  y = (yl[0] + yl[1]) + (yl[2] + yl[3]);
#endif
  c_out = c;
  s_out = s;
  return std::max(0.0f, a_ss + b_ss - 2.0f * std::sqrt(c * c + s * s) + y);
}

/// The placement carrying cloud b onto cloud a (in the clouds' units): heading from C and S, and
/// the translation that maps b's ground centroid onto a's.
Placement pose_cloud_alignment(float c, float s, vec2 a_centroid_xz, vec2 b_centroid_xz);

/// Convenience for tests and tools (not the hot path): the squared aligned distance between two
/// point sets, and the placement carrying b onto a.
float pose_points_distance_sq(std::span<const vec3, kPoseKeyPoints> a, std::span<const vec3, kPoseKeyPoints> b,
                              Placement* b_to_a);

}  // namespace foresight

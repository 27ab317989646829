#pragma once
// BvhDocument -> normalised Skeleton + Clip (metres, Y up, 30 or 60 fps, joint 0 = the moving
// pelvis), and back. See docs/BVH.md.
//
// Channel semantics (the choice matters, files disagree):
//  * A position channel REPLACES the matching component of the joint's OFFSET for that frame
//    (local translation = OFFSET with Xposition/Yposition/Zposition substituted). Never added: in
//    files that put 6 channels on every joint (the Bandai-Namco set) the non-root position
//    channels equal the OFFSET, and adding would double every bone.
//  * Rotation channels compose in the listed order, the first listed outermost:
//    "Zrotation Xrotation Yrotation" gives R = Rz * Rx * Ry (standard BVH), degrees.
//  * Local transform of a joint = translate(local translation) * R; parent space.
//
// Normalisation steps, in order:
//  1. Dummy root folding: while the ROOT has exactly one child that is not an End Site, and
//     either never moves (constant channels, or none) or only translates while that child
//     rotates (a trajectory node), its per-frame transform is composed into the child, which
//     becomes the ROOT (FK unchanged). Bandai: `joint_Root` -> `Hips` (static in 26 files, carrying
//     the travel along Z in 4 dataset-1 segments). Nothing folds when no joint moves at all (a
//     single frame): a dummy cannot be told from the pelvis there.
//  2. Unit (kAuto): body size = the largest bounding-box side of the posed body in frame 0, or
//     in a few sampled frames if larger (so a crouching first frame is still sized right), file
//     units. < 10: metres; 10..100: inches; >= 100: centimetres (a human is ~1.7 m, 67 in,
//     170 cm; the boundaries sit between the units' plausible ranges).
//  3. Up axis (kAuto): in frame 0, the dominant world axis of the pelvis -> head vector, signed
//     so the head is above the pelvis. "Head" = the first joint whose name contains "head"
//     (any case); without one, the centroid of the root's largest child subtree (the upper
//     body). Pelvis -> head is used instead of the tallest bounding-box side because a T-pose's
//     arm span equals its height. Conversion to Y up is a rotation C (no mirroring); every local
//     translation t and rotation q becomes C t and C q C^-1, so the rest pose converts too:
//       Z up: -90 deg about X, (x, y, z) -> (x, z, -y): +Z -> +Y, +Y (Z-up forward) -> -Z.
//      -Z up: +90 deg about X, (x, y, z) -> (x, -z, y).       -Y up: 180 deg about X.
//       X up: +90 deg about Z, (x, y, z) -> (-y, x, z).       -X up: -90 deg about Z.
//  4. Resampling to the target fps (0: 30 if the source is <= 45 fps, else 60): output frame k
//     samples time k / fps (lerp positions, shortest-path slerp rotations); the frame count is
//     round(duration * fps) + 1 and the last output frame is always the source's last frame, so
//     the duration is kept within half an output frame. Within 0.1% of the target, frames are
//     copied unchanged.
//  5. Quaternion signs are made continuous over time per joint (dot with previous frame >= 0).
// End Sites become joints with is_end_site = true (rest offset = End Site OFFSET, no motion).
#include "anim/bvh.hpp"
#include "anim/clip.hpp"

#include <filesystem>
#include <string>
#include <string_view>

namespace foresight {

enum class LengthUnit { kAuto, kMetres, kCentimetres, kInches };
enum class UpAxis { kAuto, kYUp, kZUp, kXUp, kNegXUp, kNegYUp, kNegZUp };

/// Metres per file unit (kAuto: 0).
float length_unit_scale(LengthUnit unit);
std::string_view length_unit_name(LengthUnit unit);
std::string_view up_axis_name(UpAxis up);

struct BvhImportOptions {
  LengthUnit unit = LengthUnit::kAuto;
  UpAxis up = UpAxis::kAuto;
  float target_fps = 0.0f;  ///< 0: 30 if the source is <= 45 fps, else 60. Otherwise > 0.
};

struct BvhImportReport {
  LengthUnit unit = LengthUnit::kAuto;  ///< What was used (detected or given).
  UpAxis up = UpAxis::kAuto;
  float source_fps = 0.0f;
  float fps = 0.0f;
  int source_frames = 0;
  int folded_root_joints = 0;  ///< Dummy ROOTs removed by step 1.
  float body_size = 0.0f;  ///< File units, as measured for unit detection.
};

/// Fails (false + error, outputs unspecified) for a document that fails bvh_validate, has no
/// frames, or a target fps that is not finite/positive (or above 1000).
bool clip_from_bvh(const BvhDocument& doc, std::string_view name, const BvhImportOptions& options,
                   Skeleton& skeleton, Clip& clip, BvhImportReport* report, std::string& error);

/// bvh_load + clip_from_bvh; the clip is named after the file stem.
bool clip_load_bvh(const std::filesystem::path& path, const BvhImportOptions& options,
                   Skeleton& skeleton, Clip& clip, BvhImportReport* report, std::string& error);

/// A BVH document for a clip: metres, Y up, frame time 1 / clip.fps. Every non-End-Site joint gets
/// "Zrotation Xrotation Yrotation"; joint 0, and any joint whose translation ever differs from its
/// rest offset, first get "Xposition Yposition Zposition". OFFSETs are the rest offsets. End Site
/// motion (if any) cannot be expressed and is dropped. Precondition: skeleton.valid(),
/// clip.num_joints == skeleton.num_joints(), clip arrays sized num_frames * num_joints.
BvhDocument bvh_from_clip(const Skeleton& skeleton, const Clip& clip);

}  // namespace foresight

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
//  0. Root placement: position channels of the joints that carry the whole body (the ROOT and
//     its single-child chain) either REPLACE their OFFSET (absolute, as above) or ADD to it
//     (relative: the channels are the motion away from the OFFSET; some exporters write that).
//     kAuto reads the file both ways and keeps the reading whose lowest point over the clip
//     (median over frames) lies nearer the floor. Other joints' position channels replace their
//     OFFSET when they are near it (Bandai) and add to it when they are near zero.
//  1. Dummy root folding: while the ROOT has exactly one child that is not an End Site, and
//     either never moves (constant channels, or none) or only translates while that child
//     rotates (a trajectory node), its per-frame transform is composed into the child, which
//     becomes the ROOT (FK unchanged). Any chain of dummies folds, one at a time. Bandai:
//     `joint_Root` -> `Hips`. Nothing folds when no joint moves at all (a single frame).
//  2. Up axis (kAuto): in frame 0, the dominant world axis of the pelvis -> head vector, signed
//     so the head is above the pelvis. "Head" = the first joint whose name contains "head"
//     (any case); without one, the centroid of the root's largest child subtree (the upper
//     body). Pelvis -> head is used instead of the tallest bounding-box side because a T-pose's
//     arm span equals its height. Conversion to Y up is a rotation C (no mirroring); every local
//     translation t and rotation q becomes C t and C q C^-1, so the rest pose converts too:
//       Z up: -90 deg about X, (x, y, z) -> (x, z, -y): +Z -> +Y, +Y (Z-up forward) -> -Z.
//      -Z up: +90 deg about X, (x, y, z) -> (x, -z, y).       -Y up: 180 deg about X.
//       X up: +90 deg about Z, (x, y, z) -> (-y, x, z).       -X up: -90 deg about Z.
//  3. Scale. A BVH file never states its unit, so for a humanoid (humanoid_map.hpp finds the
//     roles) kAuto measures the standing height from the legs (humanoid_stature: pose-proof, and
//     blind to where the rig ends its head chain) and scales it to the canonical skeleton's
//     (kCanonicalStandingHeightM): every
//     capture, whatever its unit or actor, plays on a body the scenes were built for. The report
//     names the standard unit the file most likely uses (m, cm, mm, inches, feet) and how far the
//     body is from it. A given unit or `scale` (metres per file unit) keeps the true size. For
//     a skeleton that is not a humanoid, kAuto falls back to the body's bounding box: < 10 metres,
//     10..100 inches, >= 100 centimetres.
//  4. Resampling to the target fps (0: 30 if the source is <= 45 fps, else 60): output frame k
//     samples time k / fps (lerp positions, shortest-path slerp rotations); the frame count is
//     round(duration * fps) + 1 and the last output frame is always the source's last frame, so
//     the duration is kept within half an output frame. Within 0.1% of the target, frames are
//     copied unchanged.
//  5. Quaternion signs are made continuous over time per joint (dot with previous frame >= 0).
//  6. With `canonical`, the clip is retargeted onto the canonical skeleton with the capture's
//     proportions (humanoid_retarget.hpp); joints no role takes (fingers, twist, helpers) drop.
//     A skeleton that is not a humanoid then fails, with the reason.
// End Sites become joints with is_end_site = true (rest offset = End Site OFFSET, no motion).
#include "import/bvh.hpp"
#include "anim/clip.hpp"

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace foresight {

enum class LengthUnit { kAuto, kMetres, kCentimetres, kInches, kMillimetres, kFeet };
enum class UpAxis { kAuto, kYUp, kZUp, kXUp, kNegXUp, kNegYUp, kNegZUp };
/// How the body-carrying joints' position channels relate to their OFFSET (step 0).
enum class RootPosition { kAuto, kAbsolute, kRelative };

/// Metres per file unit (kAuto: 0).
float length_unit_scale(LengthUnit unit);
std::string_view length_unit_name(LengthUnit unit);
std::string_view up_axis_name(UpAxis up);
std::string_view root_position_name(RootPosition rule);

struct BvhImportOptions {
  LengthUnit unit = LengthUnit::kAuto;
  float scale = 0.0f;  ///< Metres per file unit; > 0 wins over `unit`.
  UpAxis up = UpAxis::kAuto;
  RootPosition root = RootPosition::kAuto;
  bool canonical = false;  ///< Retarget onto the canonical skeleton (step 6).
  float target_fps = 0.0f;  ///< 0: 30 if the source is <= 45 fps, else 60. Otherwise > 0.
};

struct BvhImportReport {
  /// The unit used (given), or for a normalised humanoid the standard unit nearest to the
  /// scale used (kAuto when none is within a factor of 1.5).
  LengthUnit unit = LengthUnit::kAuto;
  float scale = 0.0f;            ///< Metres per file unit, as used.
  bool height_normalised = false;  ///< Scaled to the canonical standing height (step 3).
  UpAxis up = UpAxis::kAuto;
  RootPosition root = RootPosition::kAbsolute;  ///< The reading used (step 0).
  float source_fps = 0.0f;
  float fps = 0.0f;
  int source_frames = 0;
  int folded_root_joints = 0;  ///< Dummy ROOTs removed by step 1.
  float body_size = 0.0f;  ///< File units: the standing height (humanoid) or bounding box side.
  bool humanoid = false;   ///< humanoid_map_find found every role.
  std::string not_humanoid;  ///< Why not, when it did not.
  float standing_height_m = 0.0f;  ///< humanoid_stature() after scaling (humanoids).
  float head_height_m = 0.0f;      ///< humanoid_head_height() after scaling (humanoids).
  float lowest_foot_m = 0.0f;      ///< Median over frames of the lowest foot point (humanoids).
  /// Per source joint (after folding, End Sites included): its name, the canonical joint it
  /// became (-1: none), and whether its motion is kept (the spine's inner joints have no canonical
  /// twin, but the canonical spine is resampled along them). Filled for humanoids.
  std::vector<std::string> source_joints;
  std::vector<int> canonical_joint;
  std::vector<bool> source_joint_kept;
  /// Things a person should look at: a body outside human size, floating or sinking feet.
  std::vector<std::string> warnings;
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

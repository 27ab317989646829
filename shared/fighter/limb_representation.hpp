#pragma once
// A morphology-independent pose (paper 3.4.1, after Kulpa et al. 2005): Cartesian data divided by
// the character's own dimensions, so a pose encoded on one skeleton decodes onto any other.
//
//   pelvis     position in the root (ground placement) space: x and z divided by the leg length,
//              y = (pelvis height - standing pelvis height) / leg length (0 when standing tall)
//   legs       the foot's ground contact joint (ball of the foot, or the ankle when there is no toe
//              joint), root space, divided by the leg length; its y is the clearance above the
//              contact's flat-foot height, so a foot on the floor decodes onto the floor of any
//              character, and a planted foot stays planted. Plus the swivel angle of the knee.
//   arms       wrist relative to the shoulder joint, root-space axes, divided by the arm length
//              (shoulder -> elbow -> wrist), plus the swivel angle locating the elbow around the
//              shoulder -> wrist line.
//   segments   pelvis, each spine joint, neck, head, clavicles, hands, feet, toes: an anatomical
//              frame whose first axis is the normalised distal position (the unit vector to the
//              segment's distal joint) and whose second axis is the body's left (the clavicles:
//              up). Spine joints carry their place along the pelvis -> neck chain (0..1), so a
//              2-joint spine decodes onto a 3-joint one by interpolating frames.
//
// Decoding: the pelvis, then in one forward pass every joint: segments from their frames, limbs by
// analytic two-bone IK from the normalised end position and the swivel angle, at the target's own
// lengths; the pelvis is lowered when a grounded foot would be out of the legs' reach.
//
// Each skeleton needs a LimbModel: its rig plus, per segment, the segment's axes in the joint's own
// frame, measured once on a calibration pose that stands upright facing along the character's
// forward (the default skeleton's rest pose; a mocap clip's stance frame).
// Encode + decode onto the same skeleton reproduces the joint positions (exactly up to float
// rounding) as long as the elbows and knees bend as hinges (the default library's and most mocap).
#include "anim/clip.hpp"
#include "fighter/fighter_rig.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace foresight {

struct Morphology;

/// Joints a LimbModel can handle (stack buffers are sized by it: no allocation per pose).
inline constexpr int kLimbMaxJoints = 96;
inline constexpr int kLimbMaxSpine = 6;

enum LimbSegment : int {
  kSegPelvis,
  kSegNeck,
  kSegHead,
  kSegClavicleL,
  kSegClavicleR,
  kSegHandL,
  kSegHandR,
  kSegFootL,
  kSegFootR,
  kSegToeL,
  kSegToeR,
  kNumLimbSegments
};

/// A segment's anatomical frame in its joint's space: frame_local maps (aim, hint, aim x hint) axes.
struct SegmentAxes {
  int joint = -1;           ///< -1: this skeleton has no such segment (e.g. no toe joint).
  quat frame_local{1, 0, 0, 0};
  quat inv_frame_local{1, 0, 0, 0};
};

/// Where the middle joint bends (away from the root -> end line), in each bone's own frame.
struct LimbAxes {
  quat upper_frame_local{1, 0, 0, 0}, inv_upper_frame_local{1, 0, 0, 0};
  quat lower_frame_local{1, 0, 0, 0}, inv_lower_frame_local{1, 0, 0, 0};
  vec3 bend_upper_local{0, 0, 1};
};

struct LimbModel {
  FighterRig rig;
  std::array<SegmentAxes, kNumLimbSegments> segment;
  int num_spine = 0;
  std::array<SegmentAxes, kLimbMaxSpine> spine;
  std::array<float, kLimbMaxSpine> spine_u{};  ///< Place along pelvis -> neck, 0..1.
  std::array<LimbAxes, 2> arm_axes, leg_axes;
  std::array<int, 2> contact{-1, -1};          ///< Toe joint, or the ankle without one.
  std::array<float, 2> contact_height_m{};     ///< The contact joint above the floor, foot flat.
  float leg_length_m = 0.0f;                   ///< Mean of both legs (hip -> ankle).
  std::array<float, 2> arm_length_m{};
  float standing_pelvis_m = 0.0f;              ///< Pelvis height standing with straight legs.
  /// Per joint: what the decoder does with it (role, index); filled by limb_model_build.
  std::vector<int8_t> role, role_index;
};

/// Builds a model from a calibration pose (local arrays, num_joints entries) in which the character
/// stands upright; `contact_height_m`/`ankle_height_m`: the foot's contact joint and ankle above
/// the floor with the foot flat. False (with a reason) when the rig is not found or the skeleton
/// has more than kLimbMaxJoints joints or kLimbMaxSpine spine joints.
bool limb_model_build(const Skeleton& skeleton, std::span<const vec3> calib_local_pos_m,
                      std::span<const quat> calib_local_rot, float contact_height_m,
                      float ankle_height_m, LimbModel& model, std::string& error);
/// A morphology's model, calibrated on its rest pose (standing, arms down, facing +Z).
bool limb_model_for_morphology(const Morphology& morphology, LimbModel& model, std::string& error);
/// A mocap skeleton's model: calibrated on `calibration_frame` of `clip` (a standing frame); the
/// flat-foot heights are the lowest the contact joint and ankle get over the whole clip.
bool limb_model_from_clip(const Skeleton& skeleton, const Clip& clip, int calibration_frame,
                          LimbModel& model, std::string& error);

/// The morphology-independent pose. Fixed size: encoding and decoding never allocate.
struct LimbPose {
  vec3 pelvis_n{0.0f};
  std::array<quat, kNumLimbSegments> frame{};  ///< Root space (heading removed).
  int num_spine = 0;
  std::array<quat, kLimbMaxSpine> spine_frame{};
  std::array<float, kLimbMaxSpine> spine_u{};
  std::array<vec3, 2> arm_end_n{};
  std::array<float, 2> arm_swivel_rad{};
  std::array<vec3, 2> leg_contact_n{};
  std::array<float, 2> leg_swivel_rad{};
};

/// Encodes a pose given in local arrays (joint 0 in the space where `root` is its ground placement).
void limb_pose_encode(const Skeleton& skeleton, const LimbModel& model,
                      std::span<const vec3> local_pos_m, std::span<const quat> local_rot,
                      const Placement& root, LimbPose& out);

/// Output of a decode: local arrays (joint 0 in world space) and the model-space (world) FK.
struct PoseSpans {
  std::span<vec3> local_pos_m;
  std::span<quat> local_rot;
  std::span<vec3> global_pos_m;
  std::span<quat> global_rot;
};
/// Decodes onto `skeleton` standing on `root` (world). Local translations of non-root joints are the
/// skeleton's rest offsets. Every span has at least num_joints entries.
void limb_pose_decode(const Skeleton& skeleton, const LimbModel& model, const LimbPose& pose,
                      const Placement& root, const PoseSpans& out);

/// out = a blended towards b by weight w (0: a, 1: b); out takes a's spine layout (b's spine
/// frames are sampled at a's places). `out` may alias `a`.
void limb_pose_blend(const LimbPose& a, const LimbPose& b, float w, LimbPose& out);

/// The swivel angle of a limb (arm: the elbow, else the knee) whose root -> end axis is
/// `axis_unit` (root space), and back. The angle is measured around the axis from a reference
/// carried along by the smallest rotation from "limb hanging down" (reference: elbow back, knee
/// forward), which is singular only for a limb pointing straight up.
vec3 limb_swivel_direction(bool arm, vec3 axis_unit, float swivel_rad);
float limb_swivel_angle(bool arm, vec3 axis_unit, vec3 bend_dir);

/// An orthonormal frame whose first axis is `aim` and whose second lies in the (aim, hint) plane.
quat frame_from_axes(vec3 aim, vec3 hint);

/// Analytic two-bone IK: where the middle joint and the end land for a target, with the middle
/// joint pushed towards `bend` (unit, perpendicular to root -> target). Targets out of reach are
/// approached along the root -> target line; too close ones keep the minimum distance.
void two_bone_positions(vec3 root_m, vec3 target_m, float upper_m, float lower_m, vec3 bend,
                        vec3& mid_m, vec3& end_m);

}  // namespace foresight

#pragma once
// The upper body of the decoupled footstep paper (3.1, 5): waist 2 DOF (flexion, axial rotation)
// and each arm 4 DOF (shoulder flexion, abduction, twist; elbow flexion), carried by the pelvis
// trajectory the footstep planner produced. This file is the model: joint limits and speeds, the
// motion patterns (paper 5.1: waist erect, arms swinging opposite the legs), the body volumes and
// their collision test against the scene's boxes. upper_body_planner.hpp searches it.
//
// Frames: the pelvis frame has +Y up, +Z forward (heading 0 faces +Z), +X the actor's left
// (math/types.hpp). The waist pivot sits above the pelvis; flexion bends the torso forward about
// the pelvis' lateral axis, axial rotation twists it about its own axis first. The arms hang from
// the shoulders; flexion swings an arm forward, abduction lifts it sideways away from the body,
// twist turns it about its own axis (it matters when the elbow is bent), elbow flexion bends the
// forearm forward. Geometry defaults are the default skeleton's (anim/author/default_skeleton.cpp).
//
// Volumes: a capsule for the torso, spheres for the head and the shoulder joints (they move with
// the torso, so the waist keeps them clear), a capsule per upper arm and per forearm (with the
// hand). A capsule is tested as spheres spaced at most one radius apart (the
// union covers the capsule but for scallops of 13 % of the radius between spheres, which the
// margin more than pays for); each sphere against each nearby box by the exact point-box distance.
#include "math/types.hpp"
#include "world/scene.hpp"

#include <array>
#include <cstdint>
#include <span>

namespace foresight::terrain {

inline constexpr int kWaistDof = 2;
inline constexpr int kArmDof = 4;
inline constexpr int kMaxPartDof = 4;

/// One body part's configuration (waist: flexion, rotation; arm: flexion, abduction, twist, elbow).
using PartConfig = std::array<float, kMaxPartDof>;

enum class BodyPart : std::uint8_t { kWaist, kLeftArm, kRightArm };
const char* body_part_name(BodyPart part);
inline int part_dof(BodyPart part) { return part == BodyPart::kWaist ? kWaistDof : kArmDof; }

/// The 10 planned upper-body DOF at one frame (radians).
struct UpperBodyConfig {
  PartConfig waist{};  ///< [0] flexion (forward +), [1] axial rotation (+ turns the chest left).
  std::array<PartConfig, 2> arms{};  ///< [0] left, [1] right: flexion, abduction, twist, elbow.
  PartConfig& part(BodyPart p) { return p == BodyPart::kWaist ? waist : arms[p == BodyPart::kLeftArm ? 0 : 1]; }
  const PartConfig& part(BodyPart p) const {
    return p == BodyPart::kWaist ? waist : arms[p == BodyPart::kLeftArm ? 0 : 1];
  }
};

struct UpperBodyParams {
  // Geometry (metres), from the default skeleton.
  float waist_above_pelvis_m = 0.10f;   ///< Spine joint.
  float neck_above_waist_m = 0.40f;     ///< Spine -> Neck along the spine (0.13 + 0.14 + 0.13).
  float head_centre_above_waist_m = 0.58f;  ///< Halfway up the head (Head joint + 0.07).
  float head_forward_m = 0.01f;
  float shoulder_above_waist_m = 0.36f;  ///< Arm joints: Chest + 0.09.
  float shoulder_half_width_m = 0.175f;  ///< Clavicle 0.035 + 0.14.
  float upper_arm_m = 0.28f;
  float forearm_m = 0.34f;               ///< Elbow to the hand's end (0.26 + 0.08).
  float torso_radius_m = 0.13f;
  float head_radius_m = 0.11f;
  float upper_arm_radius_m = 0.05f;
  float forearm_radius_m = 0.045f;
  float margin_m = 0.01f;                ///< Added to every radius.
  // Limits (radians) and speeds (radians per second), per DOF.
  PartConfig waist_min{-0.30f, -0.80f, 0.0f, 0.0f}, waist_max{1.40f, 0.80f, 0.0f, 0.0f};
  PartConfig arm_min{-1.00f, 0.05f, -1.20f, 0.0f}, arm_max{2.80f, 2.40f, 1.20f, 2.40f};
  float waist_speed_radps = 2.5f;
  float arm_speed_radps = 6.0f;
  // Motion patterns (paper 5.1).
  float arm_swing_gain = 0.6f;    ///< Shoulder flexion = -gain * hip flexion of the same side.
  float arm_rest_abduction_rad = 0.10f;
  float arm_rest_elbow_rad = 0.25f;
};

/// The pelvis where the upper body is carried: the footstep planner's pelvis trajectory placed
/// along its path, and the hip flexion of each leg (the arms swing against them).
struct PelvisFrame {
  vec3 pos_m{0.0f};
  float heading_rad = 0.0f;
  float left_hip_rad = 0.0f, right_hip_rad = 0.0f;
};

/// Radii and lengths positive and finite, and few enough spheres for BodySpheres (radii not
/// too small for the limbs' lengths).
bool upper_body_params_valid(const UpperBodyParams& params);

/// The pattern O_x(t) of a part at a frame: the waist erect, the arms swinging opposite the legs.
PartConfig upper_body_pattern(const UpperBodyParams& params, BodyPart part, const PelvisFrame& frame);
/// Clamps to the part's joint limits.
PartConfig clamp_to_limits(const UpperBodyParams& params, BodyPart part, const PartConfig& q);

/// Spheres standing for a part's volumes at one frame (world metres, radius with the margin).
struct BodySpheres {
  static constexpr int kCapacity = 24;
  std::array<glm::vec4, kCapacity> spheres{};  ///< xyz centre, w radius.
  int count = 0;
};
/// The waist part's volumes (torso, head, the two shoulder joints) for waist config `waist`.
void waist_spheres(const UpperBodyParams& params, const PelvisFrame& frame, const PartConfig& waist,
                   BodySpheres& out);
/// One arm's volumes (upper arm, forearm with hand), carried by the waist config.
void arm_spheres(const UpperBodyParams& params, const PelvisFrame& frame, const PartConfig& waist,
                 BodyPart arm, const PartConfig& q, BodySpheres& out);
/// Shoulder, elbow and hand end of an arm (world metres), for tests and pictures.
struct ArmPoints {
  vec3 shoulder_m{0.0f}, elbow_m{0.0f}, hand_m{0.0f};
};
ArmPoints arm_points(const UpperBodyParams& params, const PelvisFrame& frame, const PartConfig& waist,
                     BodyPart arm, const PartConfig& q);
/// The top of the head (world metres).
vec3 head_top(const UpperBodyParams& params, const PelvisFrame& frame, const PartConfig& waist);

/// Boxes the upper body may touch, gathered once per plan (fixed capacity, no allocation).
struct UpperBodyObstacles {
  static constexpr int kCapacity = 64;
  std::array<vec3, kCapacity> min_m{}, max_m{};
  int count = 0;
  bool overflow = false;  ///< More boxes were near than fit (the plan reports it and fails safe).
};
/// The scene boxes whose top is above `min_top_m` and that come within `reach_m` of the
/// trajectory's ground bounding box. Floors and low blocks are the legs' (the ground profile).
void gather_upper_body_obstacles(const Scene& scene, std::span<const PelvisFrame> track, float reach_m,
                                 float min_top_m, UpperBodyObstacles& out);
/// True when no sphere touches a box.
bool spheres_clear(const BodySpheres& spheres, const UpperBodyObstacles& obstacles);
/// True when no volume of the whole upper body (torso, head, both arms) touches a box: what a
/// planned frame shows.
bool upper_body_clear(const UpperBodyParams& params, const PelvisFrame& frame, const UpperBodyConfig& config,
                      const UpperBodyObstacles& obstacles);

}  // namespace foresight::terrain

#pragma once
// Strike adaptation (paper 3.4.2): one retrieved strike played on a fighter of any morphology and
// bent, frame by frame, so its hit effector (wrist or ankle) reaches a target it was not recorded
// for. Per frame t (clip frames start..end):
//   1. the clip frame is encoded (LimbPose) and, over the first blend_frames, blended from the pose
//      the fighter was in when the strike began (blending in the morphology-independent space keeps
//      a foot planted in both planted);
//   2. it is decoded onto the fighter at `alignment` (retargeting, feet on the ground): the
//      effector lands at p(t);
//   3. the effector is moved to the goal p(t) + d(t), where d interpolates (smoothstep) from 0 at
//      the start frame to target - p(t_hit) at the hit frame, and back to 0 at the end frame:
//      the limb alone by analytic two-bone IK (the elbow/knee keeps its swivel) when the goal is
//      within reach, otherwise first Cyclic Coordinate Descent over the torso until the limb root is
//      within reach: punches turn the clavicle and the spine joints (chest first), kicks tilt the
//      pelvis about the support hip (which stays put) and then lean the whole body about the
//      support ankle; each within an angle budget, iterations capped; then the limb IK;
//   4. the support foot stays planted: punches never move the pelvis, so both legs keep their
//      decoded (planted) feet; kicks re-solve the support leg onto its decoded ankle, with its
//      foot's decoded orientation, after the pelvis tilt and lean.
// A goal out of reach even with the torso is approached along the root -> goal line (the limb
// straight towards it): no NaN, the error is reported.
// begin() allocates the pose buffers; pose_frame() never allocates.
#include "fighter/retarget.hpp"

#include <span>
#include <string>

namespace foresight {

struct StrikeRequest {
  LimbCharacter source;        ///< The clip's skeleton and model (default library, mocap, ...).
  const Clip* clip = nullptr;
  int start_frame = 0;         ///< t0: the first frame played.
  int hit_frame = 0;           ///< tc: where the effector must be at the target.
  int end_frame = -1;          ///< Last frame played; -1: the clip's last.
  bool kick = false;           ///< Effector: the ankle (kick) or the wrist (punch) of `side`.
  int side = kFighterLeft;
  Placement alignment;         ///< Clip space -> world (puts the clip's root on the fighter's).
  vec3 target_m{0.0f};         ///< World.
};

struct AdaptSettings {
  int blend_frames = 5;             ///< Frames blending from the current pose (0: none).
  int max_ccd_iterations = 12;      ///< Sweeps over the torso joints per frame.
  // How far CCD may turn each torso joint away from the retargeted pose, per frame (reach against
  // how far the body may bend; docs/FIGHTER_ADAPTATION.md has the trade-off measured).
  float clavicle_budget_rad = 0.45f;  ///< Punches: the striking side's clavicle.
  float spine_budget_rad = 0.45f;     ///< Punches: each spine joint.
  float pelvis_budget_rad = 0.6f;     ///< Kicks: the pelvis tilting about the support hip.
  float lean_budget_rad = 0.25f;      ///< Kicks: the whole body leaning about the support ankle.
  float step_rad = 0.25f;           ///< Largest turn of one joint in one CCD step.
};

struct AdaptedFrame {
  int clip_frame = 0;
  vec3 effector_m{0.0f};    ///< Where the wrist/ankle is (world).
  vec3 goal_m{0.0f};        ///< p(t) + d(t); the target itself at the hit frame.
  float reach_error_m = 0.0f;  ///< |effector - goal|.
  int ccd_iterations = 0;   ///< 0: the limb alone reached.
  bool reachable = true;    ///< False when the goal stayed out of reach.
};

class StrikeAdapter {
 public:
  /// Prepares a strike for `fighter`. `current_*` (optional, empty spans for none): the fighter's
  /// pose when the strike starts (local arrays, joint 0 in world). False with a reason on a bad
  /// request (frames out of order or out of the clip, joint counts not matching).
  bool begin(const StrikeRequest& request, const LimbCharacter& fighter, const AdaptSettings& settings,
             std::span<const vec3> current_local_pos_m, std::span<const quat> current_local_rot,
             std::string& error);
  /// Frames played: end - start + 1.
  int num_frames() const { return end_ - start_ + 1; }
  int hit_index() const { return hit_ - start_; }
  /// Poses frame k (0 = the start frame) into pose(); retargeted() holds it before step 3.
  AdaptedFrame pose_frame(int k);
  const PoseBuffers& pose() const { return pose_; }
  const PoseBuffers& retargeted() const { return retargeted_; }
  int effector_joint() const { return effector_; }
  /// The joint whose ground position must not move (kicks: the support foot's contact joint;
  /// punches: the rear foot, the side opposite the punching hand).
  int support_contact_joint() const;
  /// The retargeted (unadapted) effector at the hit frame, p(t_hit).
  vec3 unadapted_hit_m() const { return p_hit_; }

 private:
  void retarget_frame(int k);
  void fk();
  int solve_torso(vec3 goal);
  void solve_limb(const FighterLimb& limb, const LimbAxes& axes, vec3 goal, quat end_global_rot);

  StrikeRequest req_;
  LimbCharacter fighter_;
  AdaptSettings settings_;
  int start_ = 0, hit_ = 0, end_ = 0;
  int effector_ = -1;
  bool has_current_ = false;
  LimbPose current_{};
  vec3 p_hit_{0.0f};
  PoseBuffers retargeted_, pose_;
  std::array<float, kLimbMaxSpine + 2> spent_rad_{};  ///< CCD budget used per torso joint.
};

}  // namespace foresight

#pragma once
// Splitting a captured take that holds several strikes in a row into one strike per database
// entry (the paper keeps one hit per clip), and finding the frames the sidecar leaves out.
//
// Detection works on effector motion relative to the pelvis, so a fighter stepping or turning
// does not look like a strike:
//  * punch (wrist): a local maximum of arm reach |wrist - shoulder| / arm length that is nearly
//    straight, in front of the body (root frame), and follows a fast wrist movement;
//  * kick (ankle): a local maximum of ankle height above the take's floor that is well off the
//    ground and follows a fast ankle movement.
// Candidates from the four effectors compete: where two overlap in time, the one whose effector
// moved fastest (in body sizes per second) wins; so an arm swinging during a kick is not a punch
// ("kind from whether hand or foot moves most").
// A strike's window starts where its effector's speed (relative to the pelvis) rises above a
// fraction of its approach peak, and ends where it falls below a fraction of its retraction peak.
#include "fighter/fighter_rig.hpp"
#include "fighter_build/strike_annotation.hpp"
#include "math/types.hpp"

#include <span>
#include <vector>

namespace foresight {

/// A take's motion as the splitter reads it.
struct TakeMotionView {
  const FighterRig* rig = nullptr;
  std::span<const vec3> global_pos_m;  ///< [frame * num_joints + joint], clip space (fk_clip_positions).
  std::span<const Placement> root_track;  ///< Per frame (extract_root_track).
  int num_joints = 0;
  int num_frames = 0;
  float fps = 30.0f;
  vec3 pos(int frame, int joint) const {
    return global_pos_m[static_cast<std::size_t>(frame) * static_cast<std::size_t>(num_joints) +
                        static_cast<std::size_t>(joint)];
  }
};

struct StrikeSplitParams {
  float min_speed_body_per_s = 1.0f;  ///< Effector approach speed peak, body sizes per second.
  float min_arm_reach = 0.80f;        ///< Wrist-shoulder distance / arm length at the hit.
  float min_reach_rise = 0.12f;       ///< Reach gained over the approach (the arm was bent).
  float min_forward_arm = 0.15f;      ///< Wrist ahead of the pelvis (root frame) / arm length.
  float min_kick_height_leg = 0.45f;  ///< Ankle above the take's floor / leg length.
  float approach_s = 0.6f;            ///< Longest approach (window start .. hit).
  float retract_s = 0.8f;             ///< Longest retraction (hit .. window end).
  float min_gap_s = 0.5f;             ///< Two strikes closer than this are one strike.
  float window_speed_fraction = 0.2f; ///< Window edges: speed below this share of the peak.
};

struct DetectedStrike {
  int hit_joint = -1;
  StrikeKind kind = StrikeKind::kPunch;
  StrikeSide side = StrikeSide::kLeft;
  int start_frame = 0, hit_frame = 0, end_frame = 0;
  float peak_speed_mps = 0.0f;  ///< Effector speed relative to the pelvis, approach peak.
};

/// Every strike found in the take, in time order, windows not overlapping.
std::vector<DetectedStrike> strike_detect(const TakeMotionView& take, const StrikeSplitParams& params);

/// The window around a known hit: start/end as strike_detect finds them. Frames already >= 0 in
/// `start`/`end` are kept (the sidecar gave them).
void strike_window(const TakeMotionView& take, int hit_joint, int hit_frame, const StrikeSplitParams& params,
                   int& start, int& end);

/// The effector speed relative to the pelvis (m/s) at `frame` (central difference).
float effector_speed_mps(const TakeMotionView& take, int joint, int frame);

}  // namespace foresight

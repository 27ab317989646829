#pragma once
// Motion quality as a player sees it (issue 18): closed-loop players (the recordings' scripted
// player, seeds 1..N, from the scene's first spawn to its first goal or the one named) steer each
// controller, and
// every shown pose (the playback after the pose stage, or the raw playback without it) is
// measured:
//  * foot skate: horizontal speed of the planted part of a foot (heel or ball, as the clip plants
//    it: foot_contact.hpp) between two frames in which it stays planted, cm/s;
//  * ground error: how far the planted part is from the ground under it plus its height above the
//    clip's own floor, cm (flat scenes: what the stage moved it up or down);
//  * pops: frames where some joint's acceleration (second difference of its position) exceeds the
//    library's own within-clip 99.9th percentile of the per-frame largest joint acceleration;
//    added pops: those of them more than 10 % above what the played clip frames have themselves
//    (a pop steering, a transition's blend or the stage added; the rest are the clips' own);
//    unguarded pops: the same count on the stage's pose before its acceleration guard
//    (PoseStage::unguarded(), pose_stage.hpp 6.), with how often and how far the guard moved it;
//  * limit violations: frames where a leg bone's length differs by more than 1 cm from the
//    animated one or a knee bends the other way;
//  * response (ReplayResult::responses: of the root, which the look-ahead steers), and shown
//    response: the same measure (ResponseMeter) of the shown pose's pelvis, which is what the
//    player sees answer (the stage eases the body's turn after the root's);
//  * goals reached, and colliding frames: of the played pose (the replay's FK check) and of the
//    shown one (shown_joints_collide: the stage moves feet and lags the body's turn), the larger
//    count.
#include "library/pose_stage.hpp"
#include "lookahead/motion_tree.hpp"
#include "world/collision_world.hpp"
#include "world/scene.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace foresight::lab {

struct MotionQualityController {
  std::string name;
  MotionTreeConfig tree;
  bool pose_stage = false;
};

/// The paper's controller, steering without the pose stage, steering with it (the default).
std::vector<MotionQualityController> motion_quality_controllers(float steer_rad_per_s);

/// Moves every step block of `scene` `dz_m` along z and rebuilds `world` from it: a level nobody
/// tuned the stage for (the feet meet the edges in another phase). False with `error` when the
/// world cannot be built.
bool shift_steps(Scene& scene, CollisionWorld& world, float dz_m, std::string& error);

struct MotionQualityOptions {
  int seeds = 10;
  std::string goal;  ///< The scene's goal by name; empty: its first.
  double max_seconds = 120.0;
  int64_t expansions_per_frame = 200;
};

/// The response aim: a p95 of at most 250 ms allows 5 % of the responses over it (the
/// count that decides which side of 250 ms a p95 of many seeds falls).
inline constexpr double kResponseAim_ms = 250.0;

struct MotionQualityResult {
  std::string controller;
  bool pose_stage = false;
  int runs = 0;
  int goals_reached = 0;
  double minutes = 0.0;              ///< Shown time over every run.
  int64_t contact_samples = 0;       ///< Planted-foot frame pairs measured for skate.
  double foot_skate_cm_per_s_p50 = 0.0;
  double foot_skate_cm_per_s_p95 = 0.0;
  double foot_skate_cm_per_s_max = 0.0;
  double ground_error_cm_p95 = 0.0;
  double ground_error_cm_max = 0.0;
  int64_t pops = 0;
  double pops_per_min = 0.0;
  int64_t added_pops = 0;            ///< Pops over 10 % above the played clip frames' own (MotionLibrary::frame_acceleration_m).
  double added_pops_per_min = 0.0;
  int64_t unguarded_pops = 0;        ///< Pops of the stage's pose before its acceleration guard.
  double unguarded_pops_per_min = 0.0;
  int64_t guarded_frames = 0;        ///< Frames the guard held a change back on (PoseStage::guarded_frames)...
  double guard_offset_cm_max = 0.0;  ///< ...and the farthest it showed a joint from the unguarded pose.
  int64_t limit_violations = 0;
  int64_t discontinuities = 0;       ///< Jumps the pose stage inertialized.
  double response_ms_p50 = 0.0;
  double response_ms_p95 = 0.0;
  double shown_response_ms_p50 = 0.0;  ///< Of the shown pelvis (ResponseMeter).
  double shown_response_ms_p95 = 0.0;
  int64_t responses = 0;              ///< Command changes followed (the root's).
  int64_t responses_over_aim = 0;     ///< Those slower than kResponseAim_ms: a p95 within the aim allows 5 %.
  int64_t played_collisions = 0;     ///< Frames whose played pose overlaps the scene (ReplayRun's FK check).
  int64_t shown_collisions = 0;      ///< Frames whose shown pose (after the stage) does (shown_joints_collide).
  int64_t collisions = 0;            ///< The larger of the two.
  double goals_reached_share = 0.0;
  float pop_threshold_m = 0.0f;      ///< MotionLibrary::pop_threshold_m: the same for every controller.
};

/// Runs every controller; results in the controllers' order. `error` is set (and the result
/// empty) when the scene has no spawn or no such goal, or the player cannot plan.
std::vector<MotionQualityResult> measure_motion_quality(const MotionLibrary& library, const Scene& scene,
                                                        const CollisionWorld& world,
                                                        const std::vector<MotionQualityController>& controllers,
                                                        const MotionQualityOptions& options, std::string& error);

/// The results as a table, one controller a row (the bench and the lab print it).
std::string motion_quality_text(const std::vector<MotionQualityResult>& results);
/// One result's figures under the JSON keys issue 18 names (plus ground_error_cm_max), rounded
/// (bench::rounded); nlohmann::json, so the keys print in alphabetical order.
nlohmann::json motion_quality_json(const MotionQualityResult& r);

}  // namespace foresight::lab

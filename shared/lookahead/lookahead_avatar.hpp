#pragma once
// An avatar driven by the feasible motion tree: playback of the current segment, the tree that
// looks ahead from it, and the player's input. Per frame the owner calls, in this order:
//   set_input(...)   the player's command (camera space), validated
//   grow(budget)     spend spare time growing the tree
//   step()           play one frame; at a segment end take the tree's best child
// When the tree has no feasible child at a segment end, the avatar falls back to the library's
// idle segment placed where it stands (if that is collision-free), else holds its last pose: it
// never moves into an obstacle. With MotionTreeConfig::steer_rad_per_s > 0 (steering mode) it
// also steers the playing segment (and, standing, turns on the spot), ends settling segments
// early, filters the tree's choice while a direction is held, and recovers when wedged: a
// direction held for kWedgedAfter_s without kProgress_m of progress, while the scene has room
// ahead for its body, makes it back off (the tree follows an escape direction) and try again
// (lookahead_avatar.cpp, docs/LOOKAHEAD.md "Recovering").
#include "library/playback.hpp"
#include "library/pose_stage.hpp"
#include "world/control_input.hpp"
#include "lookahead/motion_tree.hpp"

#include <cstdint>
#include <vector>

namespace foresight {

struct AvatarStepResult {
  bool segment_changed = false;  ///< A new segment started this frame.
  bool fallback = false;         ///< ... because nothing feasible was found (idle or hold).
  int transition = -1;           ///< Graph transition taken, -1 for a fallback.
  bool steered = false;          ///< Steering mode rotated the playing segment (a new start).
  bool recovery = false;         ///< Steering mode found the avatar wedged and began backing it off.
};

class LookaheadAvatar {
 public:
  // Recovery (steering mode): no kProgress_m in kWedgedAfter_s while a direction is held is
  // wedged (a side step is 0.26 m: stepping left and right is no progress); the escape lasts
  // until kBackOff_m from where it began or kEscapeMax_s. The way ahead is open when a
  // straight kProbe_m leg within kProbeSpread_rad of the command is free for the body.
  static constexpr float kProgress_m = 0.3f;
  static constexpr float kWedgedAfter_s = 1.5f;
  static constexpr float kBackOff_m = 0.6f;
  static constexpr float kEscapeMax_s = 2.5f;
  static constexpr float kProbe_m = 1.0f;
  static constexpr float kProbeSpread_rad = 0.7f;  // 40 deg
  static constexpr float kSameCommandCos = 0.7f;   // within 45 deg: the same key
  static constexpr float kStandingTurn_rad_per_s = 3.14f;  // 180 deg/s, a brisk turn on the spot
  // Steering (steer()): the way the root goes is from where it stands to where the playing
  // segment takes it kSteerAheadFrames on (less than kSteerAheadMin_m: going nowhere, and only
  // the heading decides); a way kWayOff_rad or more off the key is steered onto it, and a way
  // within it but more than kWayNearKey_rad off is not steered away from the key by the heading.
  static constexpr int kSteerAheadFrames = 4;       // 0.13 s at 30 fps: averages a stride's sway out
  static constexpr float kSteerAheadMin_m = 0.05f;
  static constexpr float kWayOff_rad = 0.44f;       // 25 deg
  static constexpr float kWayNearKey_rad = 0.09f;   // 5 deg
  // A segment going sideways (its way kSidewaysFrom_rad to kSidewaysTo_rad off its facing: a side
  // step) is steered at kSidewaysSteerShare of the steering rate: aiming its way at the key turns
  // its body as far, and a side step spun at the full rate pops its knees (docs/MOTION_QUALITY.md).
  static constexpr float kSidewaysFrom_rad = 0.785f;  // 45 deg
  static constexpr float kSidewaysTo_rad = 2.356f;    // 135 deg: a walk backwards is not sideways
  static constexpr float kSidewaysSteerShare = 1.0f / 3.0f;  // 180 deg/s of 540 (1/4, 1/6, 1/12: measured)
  // A fallback whose idle does not fit where the segment ends looks this far back (and turned).
  static constexpr float kStandSearch_m = 0.5f;
  static constexpr float kStandSearchStep_m = 0.1f;
  // After a fallback nothing is turned (on the spot or steered) while the jump to the stand is
  // still being shown (the pose stage carries it over its inertialize_s): turned at once, the
  // offset still showing the body where the segment ended swung with the turn (into the pillar
  // that ended the walk; a Bandai backward walk's start steered on its first frame).
  static constexpr float kFallbackSettle_s = PoseStageConfig{}.inertialize_s;

  /// Spawns in `start_segment` at `start`. The caller checks that this placement is free.
  LookaheadAvatar(const MotionLibrary& library, const CollisionWorld& world, MotionTreeConfig config,
                  int start_segment, const Placement& start);

  /// Non-finite or over-long directions are refused: the input becomes "stop" and is counted.
  void set_input(const ControlInput& input);
  GrowResult grow(const GrowBudget& budget);
  /// `veto` (optional) rules out children at the decision, the idle fallback and, in steering
  /// mode, rotations of the playing segment.
  AvatarStepResult step(const ChildVeto* veto = nullptr);

  const PlaybackState& playback() const { return playback_; }
  Placement root() const { return playback_root(library_, playback_); }
  /// Where the playing segment takes the root over the next kSteerAheadFrames (to its end at
  /// most), from where it stands: the way steering holds onto the key. Under kSteerAheadMin_m on
  /// the segment's first kSteerAheadFrames, where it takes the root by its end (a move that sets
  /// off slowly).
  vec2 way_ahead() const;
  const MotionTree& tree() const { return tree_; }
  MotionTree& tree() { return tree_; }
  const ControlInput& input() const { return input_; }
  /// Segment ends where nothing feasible was found. A held pose re-decides every frame, so each
  /// frame of a hold counts once.
  int fallbacks() const { return fallbacks_; }
  int rejected_inputs() const { return rejected_inputs_; }
  /// Times steering mode found the avatar wedged or dithering and backed it off.
  int recoveries() const { return recoveries_; }
  bool recovering() const { return recover_s_ >= 0.0f; }
  /// The segment used when nothing feasible is found (-1 if the library has no idle segment).
  int fallback_segment() const { return fallback_segment_; }

 private:
  /// The direction the tree and the steering follow: the player's, or the escape direction
  /// while recovering.
  vec2 steering_command() const;
  /// True when a recovery began.
  bool watch_progress();
  bool way_ahead_open(vec2 command) const;
  bool steer(const ChildVeto* veto);
  float intended_heading() const;
  bool turn_on_spot(const ChildVeto* veto);
  bool rotate_playing(float turn, const ChildVeto* veto, bool keep_way_on);
  Placement turned_start(float turn) const;
  float frame_turn(float rad_per_s) const;
  bool is_standing_loop(int segment) const { return standing_loop_[static_cast<size_t>(segment)] != 0; }
  /// A turn on the spot: a turning segment that does not travel (the library's idle_turn_*).
  bool is_spot_turn(int segment) const {
    const uint32_t tags = library_.graph.segments[static_cast<size_t>(segment)].tags;
    return (tags & kTagTurn) && !(tags & kTagLocomotion);
  }
  bool has_way_on(int segment, const Placement& start, int depth) const;
  bool may_end_early() const;
  int select_child(const ChildVeto* veto);
  void find_traps();

  static constexpr int kWayOnDepth = 2;  // segments a rotation must leave open ahead
  static constexpr float kEarlyEndMove_m = 0.02f;
  static constexpr float kEarlyEndTurn_rad = 0.035f;  // 2 deg
  static constexpr float kEarlyEndRise_m = 0.05f;  // the pelvis's rise or fall left (a stand-up's last 3 frames)
  static constexpr float kWalkingDeadZone_rad = 0.26f;     // 15 deg
  static constexpr float kFacingCone_rad = 0.79f;          // 45 deg either side of the command
  static constexpr float kFacingStep_rad = 0.087f;         // 5 deg
  static constexpr float kFacedWithin_rad = 0.017f;        // 1 deg
  static constexpr float kSameFacingCos = 0.985f;          // a command within 10 deg: same search

  const MotionLibrary& library_;
  const CollisionWorld& world_;
  MotionTree tree_;
  PlaybackState playback_;
  ControlInput input_;
  int fallback_segment_ = -1;
  int crouch_fallback_segment_ = -1;  ///< Where a crouching avatar falls back to (-1: none).
  int fallbacks_ = 0;
  int settle_frames_ = 0;  ///< Frames after a fallback that nothing is turned (kFallbackSettle_s).
  int rejected_inputs_ = 0;
  float body_clearance_m_ = 0;  ///< The library's walker (moving_body_clearance_m, less steering room).
  float body_height_m_ = 0;     ///< Its lowest moving body (lowest_moving_body_m).
  // Progress watch and recovery (steering mode, while a direction is held).
  vec2 watch_from_{0.0f};
  float watch_s_ = -1;  ///< < 0: not watching.
  vec2 escape_{0.0f};
  vec2 escape_from_{0.0f};
  vec2 escape_command_{0.0f};  ///< The player's direction when the escape began.
  float recover_s_ = -1;       ///< < 0: not recovering.
  int recoveries_ = 0;
  // turn_on_spot(): the heading searched for this standing loop, place and command.
  bool facing_searched_ = false;
  bool has_facing_ = false;
  vec2 facing_for_{0.0f};
  vec2 facing_at_{0.0f};
  int facing_segment_ = -1;
  float facing_ = 0;
  std::vector<uint8_t> standing_loop_;  ///< Per graph segment: a held pose that goes nowhere.
  std::vector<uint8_t> ends_standing_;  ///< Per graph segment: a standing loop may follow it.
  std::vector<int> traps_;              ///< find_traps(): segments of the root's trap children.
};

/// The idle segment a library falls back to: tagged idle (not fight), crouching or not as asked,
/// moving least. -1 if it has none.
int find_fallback_segment(const MotionLibrary& library, bool crouching = false);

/// Where a new avatar starts: the fallback idle, or in a library without one (a folder of
/// locomotion captures) the non-fight segment with the slowest root. -1 for an empty library.
int find_spawn_segment(const MotionLibrary& library);

}  // namespace foresight

#pragma once
// An avatar driven by the feasible motion tree: playback of the current segment, the tree that
// looks ahead from it, and the player's input. Per frame the owner calls, in this order:
//   set_input(...)   the player's command (camera space), validated
//   grow(budget)     spend spare time growing the tree
//   step()           play one frame; at a segment end take the tree's best child
// When the tree has no feasible child at a segment end, the avatar falls back to the library's
// idle segment placed where it stands (if that is collision-free), else holds its last pose: it
// never moves into an obstacle. With MotionTreeConfig::steer_rad_per_s > 0 (steering mode) it
// also steers the playing segment, ends settling segments early and filters the tree's choice
// while a direction is held (lookahead_avatar.cpp, docs/LOOKAHEAD.md).
#include "library/playback.hpp"
#include "lookahead/control_input.hpp"
#include "lookahead/motion_tree.hpp"

#include <cstdint>
#include <vector>

namespace foresight {

struct AvatarStepResult {
  bool segment_changed = false;  ///< A new segment started this frame.
  bool fallback = false;         ///< ... because nothing feasible was found (idle or hold).
  int transition = -1;           ///< Graph transition taken, -1 for a fallback.
  bool steered = false;          ///< Steering mode rotated the playing segment (a new start).
};

class LookaheadAvatar {
 public:
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
  const MotionTree& tree() const { return tree_; }
  MotionTree& tree() { return tree_; }
  const ControlInput& input() const { return input_; }
  /// Segment ends where nothing feasible was found. A held pose re-decides every frame, so each
  /// frame of a hold counts once.
  int fallbacks() const { return fallbacks_; }
  int rejected_inputs() const { return rejected_inputs_; }
  /// The segment used when nothing feasible is found (-1 if the library has no idle segment).
  int fallback_segment() const { return fallback_segment_; }

 private:
  bool steer(const ChildVeto* veto);
  bool is_standing_loop(int segment) const { return standing_loop_[static_cast<size_t>(segment)] != 0; }
  bool has_way_on(int segment, const Placement& start, int depth) const;
  bool may_end_early() const;
  int select_child(const ChildVeto* veto);
  void find_traps();

  static constexpr int kWayOnDepth = 2;  // segments a rotation must leave open ahead
  static constexpr float kEarlyEndMove_m = 0.02f;
  static constexpr float kEarlyEndTurn_rad = 0.035f;  // 2 deg

  const MotionLibrary& library_;
  const CollisionWorld& world_;
  MotionTree tree_;
  PlaybackState playback_;
  ControlInput input_;
  int fallback_segment_ = -1;
  int fallbacks_ = 0;
  int rejected_inputs_ = 0;
  std::vector<uint8_t> standing_loop_;  ///< Per graph segment: a held pose that goes nowhere.
  std::vector<uint8_t> ends_standing_;  ///< Per graph segment: a standing loop may follow it.
  std::vector<int> traps_;              ///< find_traps(): segments of the root's trap children.
  std::vector<int> visit_;              ///< Scratch stack (reserved once).
};

/// The idle segment a library falls back to: tagged idle (not crouch, not fight), moving least.
int find_fallback_segment(const MotionLibrary& library);

/// Where a new avatar starts: the fallback idle, or in a library without one (a folder of
/// locomotion captures) the non-fight segment with the slowest root. -1 for an empty library.
int find_spawn_segment(const MotionLibrary& library);

}  // namespace foresight

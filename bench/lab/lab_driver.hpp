#pragma once
// Driving a recording frame by frame (scripted/replay.hpp's ReplayRun, the same loop as
// replay_recording) to look inside the avatar at chosen moments: its state for Fig. 10 and for
// timing MotionTree::grow on realistic trees.
#include "scripted/recording.hpp"
#include "scripted/replay.hpp"

#include <string>
#include <vector>

namespace foresight::lab {

/// What the avatar was doing at one moment.
struct DriveState {
  double time_s = 0.0;  ///< Display time of the last frame played.
  int segment = 0;
  Placement segment_start;
  int incoming_transition = -1;
  Placement avatar;          ///< Root placement now.
  vec2 command_world{0.0f};  ///< The held command as a world ground direction.
};

/// The state after the last display frame at or before each of `times_s` (ascending), or fewer
/// states when the run ends first. Empty (with `error`) when the replay cannot start.
std::vector<DriveState> drive_states_at(const MotionLibrary& library, const CollisionWorld& world,
                                        const Recording& recording, const ReplayConfig& config,
                                        const std::vector<double>& times_s, std::string& error);

/// `count` moments evenly spread from the recording's first sample to its last.
std::vector<double> evenly_spread_times(const Recording& recording, int count);

}  // namespace foresight::lab

namespace foresight::lab {

/// Where a strategy's nodes go: the tree size just before each root advance and the share of it
/// the advance keeps (the chosen child's subtree). Explains Fig. 9: every strategy adds about the
/// same number of nodes for a budget; the average size is decided by how much survives.
struct TreeTurnover {
  double avg_tree_size = 0.0;  ///< Same definition as ReplayResult::avg_tree_size.
  int64_t nodes_added = 0;
  int advances = 0;
  double mean_size_before_advance = 0.0;
  double mean_kept_share = 0.0;  ///< Mean over advances of kept / size before.
  double mean_kept_depth = 0.0;  ///< Mean depth (below the new root) of the nodes kept.
};

/// The replay's loop (replay.hpp's time model: grow once per display frame, floor(t * fps) clip
/// frames by t, spawn in the idle segment) run with a LookaheadAvatar directly so the tree can be
/// watched around each advance. Runs to config.max_seconds or the recording's end plus
/// config.grace_after_end_s, whichever is first; ignores stop_at_goal and wall_clock_spare_s.
TreeTurnover drive_turnover(const MotionLibrary& library, const CollisionWorld& world,
                            const Recording& recording, const ReplayConfig& config,
                            std::string& error);

}  // namespace foresight::lab

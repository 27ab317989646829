#pragma once
// Replaying a recording (paper 5.1): the same commands drive a LookaheadAvatar under any
// exploration strategy and budget, and the run is measured (tree size, responsiveness, collisions).
//
// Time model. Display frames k = 0, 1, ... at t_k = k * frame_interval_s. Per display frame:
//   set_input(recording_input_at(t_k))   the command held at t_k
//   grow(budget)                         expansions_per_frame, or a wall-clock deadline
//   step() once per clip frame due       clip time advances with display time: by t_k the avatar
//                                        has played floor(t_k * fps) clip frames (fps of the
//                                        library's clips), so a 1/15 s interval plays 2 per frame
// then the root is recorded, the goal tested and the shown poses re-checked for collisions from
// their FK joints (independently of the precomputed volumes the tree uses).
// The avatar spawns in the library's idle segment (find_fallback_segment) at the recording's start.
//
// Deterministic with an expansion budget: the same recording, library, scene and config give the
// same result bit for bit. No allocation per frame beyond the result vectors.
#include "library/motion_library.hpp"
#include "library/pose_check.hpp"
#include "lookahead/lookahead_avatar.hpp"
#include "scripted/recording.hpp"
#include "scripted/response_meter.hpp"
#include "lookahead/transition_statistics.hpp"
#include "world/collision_world.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace foresight {

struct ReplayConfig {
  MotionTreeConfig tree;
  double frame_interval_s = 1.0 / 30.0;  ///< Display frame interval (the paper's x axis).
  int64_t expansions_per_frame = 200;    ///< Spare budget per display frame, deterministic.
  double wall_clock_spare_s = 0;         ///< If > 0: a deadline this many seconds per frame instead.
  double max_seconds = 300;              ///< Give up after this much simulated time.
  /// Also give up this long after the recording's last sample when the goal was not reached
  /// (nothing new happens after it). Negative: only max_seconds.
  double grace_after_end_s = 10;
  bool stop_at_goal = true;
  TransitionStatistics statistics;  ///< For strategies 3/4 (learn_statistics); may be empty.
};

inline constexpr double kStallSeconds = 3.0;
inline constexpr float kStallProgress_m = 0.3f;

struct ReplayResult {
  bool reached_goal = false;
  double time_to_goal_s = 0;  ///< t_k of the first display frame with the root in the goal.
  double seconds = 0;         ///< Simulated time replayed (display frames * interval).
  int fallbacks = 0;
  /// Stalls: a key held for kStallSeconds while the root got no kStallProgress_m from where it
  /// was (wedged, or dithering in place); each such stretch counts once.
  int stalls = 0;
  int recoveries = 0;  ///< LookaheadAvatar::recoveries(): backed off when wedged (steering mode).
  int64_t colliding_frames = 0;  ///< Shown poses re-checked from FK (must be 0).
  double avg_tree_size = 0;      ///< Mean over display frames of tree.num_nodes() after growing.
  /// Mean angle between the commanded world direction and the avatar's velocity (root
  /// displacement over the last ~0.2 s), over frames with a command and a speed > 0.2 m/s.
  double mean_command_angle_deg = 0;
  /// Per command-direction change (a command > 30 deg from the last one, or a command after a
  /// stop): how long until the velocity was within 30 deg of it. Changes superseded or cancelled
  /// (stop) before the avatar follows are not counted.
  std::vector<Response> responses;
  std::vector<int> transitions_taken;  ///< Graph transitions entered, in order (strategy 3).
  std::vector<vec2> path;              ///< Root position per display frame.
  std::vector<int> segments;           ///< Segment playing per display frame (traces, diagnosis).
  std::string error;                   ///< Non-empty when the replay could not start.
};

/// One display frame at a time: what replay_recording runs, and what the recording generator
/// steers with its scripted player (so a recording replayed with the generator's config
/// reproduces the generator's run exactly).
class ReplayRun {
 public:
  ReplayRun(const MotionLibrary& library, const CollisionWorld& world, const Placement& start,
            vec2 goal_pos_m, float goal_radius_m, const ReplayConfig& config);

  /// False (with error()) when the library has no idle segment, the spawn is not free for it,
  /// the statistics do not fit the library or the config is not usable.
  bool ok() const { return avatar_.has_value(); }
  const std::string& error() const { return result_.error; }

  /// Plays display frame frame_index() with this input (see the time model above).
  void frame(const ControlInput& input);
  /// Goal reached (with stop_at_goal) or max_seconds simulated (or not ok()).
  bool done() const { return done_; }
  int64_t frame_index() const { return frame_; }
  /// t of the next display frame.
  double time_s() const { return static_cast<double>(frame_) * config_.frame_interval_s; }

  const LookaheadAvatar& avatar() const { return *avatar_; }
  const ReplayResult& result() const { return result_; }
  /// The result with the means computed; call once, after the last frame.
  ReplayResult finish();

 private:
  void check_shown_pose();
  void count_stalls(double t_s, vec2 pos, bool key_held);

  const MotionLibrary& library_;
  const CollisionWorld& world_;
  ReplayConfig config_;
  std::optional<LookaheadAvatar> avatar_;
  vec2 goal_pos_m_;
  float goal_radius_m_;
  double fps_ = 30;
  int64_t frame_ = 0;
  int64_t clip_frames_played_ = 0;
  bool done_ = false;
  ReplayResult result_;
  // Metrics.
  double tree_size_sum_ = 0;
  bool stall_watch_ = false;  ///< A key is held: stall_from_ is where progress is measured from.
  vec2 stall_from_{0.0f};
  double stall_since_s_ = 0;
  std::optional<ResponseMeter> response_;  ///< Of the root (set up once the config checks out).
  // Scratch for the FK re-check (sized once).
  PoseCheckScratch check_scratch_;
};

/// The responses' times (ms), in order.
std::vector<double> response_ms(const ReplayResult& result);

/// Replays the recording from its start until the goal (with stop_at_goal), max_seconds, or
/// grace_after_end_s past its last sample. result.error is set when it could not start.
ReplayResult replay_recording(const MotionLibrary& library, const CollisionWorld& world,
                              const Recording& recording, const ReplayConfig& config);

/// Strategy 3's priorities: replays the training recording with strategy kCommand (the rest of
/// `config` as given) and learns from the transitions taken (transition_statistics_learn).
/// Empty when the replay could not start.
TransitionStatistics learn_statistics(const MotionLibrary& library, const CollisionWorld& world,
                                      const Recording& training, const ReplayConfig& config);

}  // namespace foresight

#pragma once
// The upper-body planner of the decoupled footstep paper (5.2): once the footstep planner has fixed
// the pelvis trajectory qR(t), the waist is planned first, then each arm with the waist's motion
// fixed (prioritised, decoupled). Each part searches a CT-roadmap: nodes are (configuration, time
// frame); the roadmap starts with the part's motion pattern and a few common variants of it
// (offsets from the pattern: bent, turned, raised, tucked), and grows when the search is stuck.
//
// The search is the paper's best-first planning forward in time (Fig. 5): from the node at frame
// t, the successors at t + 1 are the roadmap's configurations steered towards at the part's joint
// speed, tried nearest to the pattern O(t + 1) first; a successor is kept when its volumes touch no
// box. When every successor fails, new roadmap nodes are grown a distance r from the current one
// (seeded, deterministic); when those fail too, the search backtracks to the previous frame and
// tries its next successor. A (frame, configuration cell) visited once is never tried again, so the
// search ends: at the last frame (kOk), out of successors (kNoPath), or out of budget (kBudget).
//
// Beyond the paper, two kinds of foresight (docs/TERRAIN.md): for each run of frames where the
// pattern itself is blocked, the latest frame to leave the pattern for a roadmap configuration
// that is clear through the run (from then on such successors come first); and the previous
// window's plan as a guide, tried first where it still applies.
//
// Deterministic for the same inputs and config; after upper_body_planner_init nothing allocates.
#include "terrain/footstep_planner.hpp"
#include "terrain/upper_body.hpp"
#include "math/splitmix64.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace foresight::terrain {

inline constexpr int kMaxUpperBodyFrames = 256;  ///< Frames of one plan (8.5 s at 30 Hz).
inline constexpr int kMaxRoadmapNodes = 40;      ///< Per part: initial variants + grown nodes.

struct UpperBodyPlannerConfig {
  UpperBodyParams body;
  int max_checks_per_part = 4000;  ///< Collision checks a part may spend. [> 0]
  int grow_tries = 3;               ///< New roadmap nodes grown at a stuck node before backtracking.
  float grow_distance_rad = 0.4f;   ///< r: how far from the current node a new node is grown.
  float visit_cell_rad = 0.04f;     ///< Configurations closer than this at a frame count as the same.
  std::uint64_t seed = 1;
};

enum class UpperBodyStatus : std::uint8_t {
  kOk,
  kInvalidConfig,     ///< The planner was not initialised with a valid config.
  kBadInput,          ///< No frames, too many, a non-finite pelvis or start, or dt <= 0.
  kTooManyObstacles,  ///< More boxes near the path than UpperBodyObstacles holds.
  kStartInCollision,  ///< The part's configuration at frame 0 already touches a box.
  kNoPath,            ///< Every successor and grown node failed back to frame 0.
  kBudget,            ///< max_checks_per_part spent before reaching the last frame.
};
const char* upper_body_status_name(UpperBodyStatus status);

/// What the search for one part did (deterministic counters).
struct UpperBodyPartStats {
  UpperBodyStatus status = UpperBodyStatus::kBadInput;
  int frames_reached = 0;   ///< Deepest frame reached + 1.
  int checks = 0;           ///< Collision checks.
  int backtracks = 0;
  int grown = 0;            ///< Roadmap nodes grown.
  float mean_deviation_rad = 0.0f;  ///< Mean |q - O(t)| over the plan (0: the pattern throughout).
  float max_deviation_rad = 0.0f;
};

struct UpperBodyPlan {
  UpperBodyStatus status = UpperBodyStatus::kBadInput;
  BodyPart failed_part = BodyPart::kWaist;  ///< Meaningful when status is not kOk.
  int num_frames = 0;                       ///< The track's length on kOk, 0 otherwise.
  std::array<UpperBodyConfig, kMaxUpperBodyFrames> frames{};
  std::array<UpperBodyPartStats, 3> parts{};  ///< By BodyPart.
};

/// The planner's workspace, sized once by upper_body_planner_init (the only allocation).
struct UpperBodyPlanner {
  UpperBodyPlannerConfig config;
  bool valid = false;
  std::uint32_t stamp = 0;  ///< Generation of the visited table (no clearing between parts).
  std::vector<std::uint64_t> visited_key;
  std::vector<std::uint32_t> visited_stamp;
  struct Node {
    PartConfig q{};
    int grown = 0;  ///< Roadmap nodes grown from here so far.
  };
  std::array<Node, kMaxUpperBodyFrames> stack{};
  std::array<PartConfig, kMaxRoadmapNodes> roadmap{};  ///< Offsets from the pattern.
  int roadmap_size = 0;
  SplitMix64 rng;
};

/// Validates the config and sizes the workspace. False (planner.valid false) on a bad config.
bool upper_body_planner_init(UpperBodyPlanner& planner, const UpperBodyPlannerConfig& config);

/// Plans waist, then left arm, then right arm along `track` (frame 0 = now, spaced dt_s), from
/// `start` (the configuration shown now; clamped to the limits) against `obstacles`. On kOk
/// `plan.frames[0..track.size())` holds every frame; otherwise num_frames is 0, failed_part and
/// the part's stats say why. No allocation.
///
/// `guide`: the previous window's plan from where this one starts (frame 0 = track frame 0), the
/// upper body's counterpart of the footstep window's re-seeding (s2..sn, s_init). At each frame
/// it covers it is the first successor tried, so a plan that is still feasible is kept: the
/// window that saw an obstacle coming keeps steering around it, instead of a new search starting
/// over (and possibly too late) from the committed pose.
UpperBodyStatus upper_body_plan(UpperBodyPlanner& planner, std::span<const PelvisFrame> track, float dt_s,
                                const UpperBodyObstacles& obstacles, const UpperBodyConfig& start,
                                UpperBodyPlan& plan, std::span<const UpperBodyConfig> guide = {});

/// The patterns at frame 0 of a track: where a fresh actor starts.
UpperBodyConfig upper_body_pattern_config(const UpperBodyParams& params, const PelvisFrame& frame);

/// The pelvis trajectory of a footstep plan, sampled every dt_s at walking speed `speed_mps`
/// (each step lasts its pelvis advance / speed, at least one frame) and placed along the plan's
/// path: frame 0 is phase 0 of the first step. `first_swing_left` says which leg swings in step 1
/// (they alternate). Returns the frames written (at most out.size()); `first_step_frames` gets the
/// frame at which step 1 ends (where the next plan, after the window slides, starts).
int pelvis_track_from_plan(const FootstepPlan& plan, const WalkParams& walk, const GroundPath& path,
                           float speed_mps, float dt_s, bool first_swing_left, std::span<PelvisFrame> out,
                           int& first_step_frames);

}  // namespace foresight::terrain

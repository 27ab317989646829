#pragma once
// The footstep planner of the decoupled footstep paper (4.2): a sliding window of the next n step
// lengths q = (s1, ..., sn), each on a grid of m + 1 values in [s_min, s_max]. From the seed q_init
// a breadth-first search (neighbours: one step one grid notch longer or shorter; from a
// configuration whose step i fails only steps 1..i are changed, since step i depends on them
// alone) finds a near collision-free configuration; a steepest-descent local optimisation of the cost then stops at
// the first configuration whose neighbours are all worse. Only the first step is consumed; the
// window slides by one step and is re-seeded with (s2, ..., sn, s_init).
//
// A configuration is collision-free when every foot lands on ground (foothold_fit: not in a gap,
// not straddling an edge), every step is within the walk's height limits and its swing clears the
// profile (walk_step_plan), and, beyond the paper, the last foothold still has a reachable next
// foothold (so the window does not lead into a dead end one step later).
//
// Cost per step (effort and deviation from the neutral step):
//   w_length * ((s - s_neutral) / s_neutral)^2 + w_up * climb + w_down * descent
//   + w_lift * swing lift + w_pitch * |landing foot pitch|.
//
// Footsteps are distances along the profile (GroundProfile); the planner works in its 2D cut.
// Deterministic; after footstep_planner_init nothing allocates.
#include "terrain/procedural_walk.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace foresight::terrain {

inline constexpr int kMaxWindowSteps = 4;   ///< n limit: the search space is (m + 1)^n.
inline constexpr int kMaxStepIntervals = 16;  ///< m limit.

struct FootstepPlannerConfig {
  int window_steps = 3;       ///< n. [1, kMaxWindowSteps]
  int intervals = 13;         ///< m: the step range is cut into m intervals. [1, kMaxStepIntervals]
  float step_min_m = 0.25f;   ///< s_min, ankle to ankle along the profile. [> 0]
  float step_max_m = 0.90f;   ///< s_max. [> step_min_m]
  float step_neutral_m = 0.65f;  ///< s_init (snapped to the nearest grid value).
  float w_length = 1.0f;      ///< Per squared relative deviation from s_neutral.
  float w_up = 1.0f;          ///< Per metre climbed.
  float w_down = 0.5f;        ///< Per metre descended.
  float w_lift = 0.5f;        ///< Per metre of swing-curve lift.
  float w_pitch = 0.2f;       ///< Per radian of landing foot pitch.
  bool require_next_foothold = true;  ///< The viability test on the window's last foothold.
  WalkParams walk;
};

enum class FootstepStatus : std::uint8_t {
  kOk,
  kInvalidConfig,  ///< The planner was not initialised with a valid config.
  kEmptyProfile,   ///< The profile has no samples.
  kBadStart,       ///< The stance (or rear) foot is not on ground of the profile (or NaN).
  // No collision-free window; the dominant reason among the failed checks:
  kWall,           ///< Ground ahead too high to climb (a vertical wall).
  kCliff,          ///< Ground ahead too low to step down.
  kGap,            ///< Only gaps within reach.
  kObstacle,       ///< Something too high to swing the foot over.
  kUnevenGround,   ///< Only edges or too steep slopes to stand on.
  kUnreachable,    ///< Key frames out of the legs' reach.
  kEndOfProfile,   ///< The window runs off the end of the profile (cut a longer one).
};
const char* footstep_status_name(FootstepStatus status);

/// Where the window stands: the rear (next swing) foot and the stance foot, ankle distances along
/// the profile, and the seed of the next search.
struct FootstepWindow {
  float rear_x_m = 0.0f;
  float stance_x_m = 0.0f;
  bool seeded = false;  ///< False: q_init = (s_init, ..., s_init).
  std::array<std::int8_t, kMaxWindowSteps> seed_index{};  ///< Grid index of each step.
};

struct FootstepPlan {
  FootstepStatus status = FootstepStatus::kEmptyProfile;
  int num_steps = 0;  ///< n on success, 0 otherwise.
  std::array<std::int8_t, kMaxWindowSteps> step_index{};
  std::array<float, kMaxWindowSteps> step_length_m{};
  std::array<Foothold, kMaxWindowSteps> footholds{};  ///< Landing of each step.
  std::array<WalkStep, kMaxWindowSteps> steps{};      ///< Ready to sample (walk_step_sample).
  float cost = 0.0f;
  // What the search did (deterministic counters).
  int configs_evaluated = 0;  ///< Configurations tested for feasibility (BFS + descent).
  int bfs_expanded = 0;       ///< Configurations popped from the BFS queue.
  int descent_moves = 0;      ///< Improving moves of the local optimisation.
  int step_checks = 0;        ///< walk_step_plan calls (memoised per plan).
  int foothold_checks = 0;    ///< foothold_fit calls (memoised per plan).
};

/// The planner's fixed workspace, sized once by footstep_planner_init (the only allocation).
struct FootstepPlanner {
  FootstepPlannerConfig config;
  bool valid = false;
  float step_delta_m = 0.0f;  ///< (s_max - s_min) / m.
  int neutral_index = 0;
  int num_configs = 0;        ///< (m + 1)^n.
  std::uint32_t stamp = 0;    ///< Generation of the memo tables (no clearing between plans).
  struct FootholdEntry { Foothold foothold; WalkStatus status; std::uint32_t stamp; };
  struct StepEntry { float cost; WalkStatus status; std::uint32_t stamp; };
  std::vector<FootholdEntry> footholds;  ///< By (step i in 1..n+1, cumulative index K).
  std::vector<StepEntry> step_memo;      ///< By (i, K_{i-1}, k_{i-1}, k_i).
  std::vector<std::uint32_t> viable;     ///< By K_n: stamp * 2 + viable bit.
  std::vector<std::uint64_t> visited;    ///< BFS visited bitset over configurations.
  std::vector<std::uint32_t> queue;      ///< BFS queue of encoded configurations.
  std::array<int, 8> failure_counts{};   ///< By WalkStatus, fresh failures of the current plan.
};

/// Validates the config and sizes the workspace. False (planner.valid false) on a bad config:
/// n or m out of range, s_min <= 0, s_max <= s_min, or non-finite values.
bool footstep_planner_init(FootstepPlanner& planner, const FootstepPlannerConfig& config);

/// Plans the window. On kOk `plan` holds n steps; otherwise num_steps is 0 and status says why
/// (never NaN anywhere). No allocation.
FootstepStatus footstep_plan(FootstepPlanner& planner, const GroundProfile& profile,
                             const FootstepWindow& window, FootstepPlan& plan);

/// Consumes the plan's first step: rear <- stance, stance <- first landing, seed (s2..sn, s_init).
/// Requires plan.status == kOk.
void footstep_window_slide(const FootstepPlanner& planner, const FootstepPlan& plan,
                           FootstepWindow& window);

/// The baseline of Fig. 8(a): one fixed step length, no search. Checks the next step of length
/// step_m from the window and returns its walk status (kOk or why it fails); on kOk `out` is the
/// step and the window has slid. What happens without footstep planning.
WalkStatus fixed_step_advance(const GroundProfile& profile, const WalkParams& params, float step_m,
                              FootstepWindow& window, WalkStep& out);

}  // namespace foresight::terrain

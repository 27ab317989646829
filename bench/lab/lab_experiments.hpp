#pragma once
// The paper's experiments (Lin et al., feasible motion tree, section 5) replayed from the shipped
// recordings, plus the navigation comparison the paper left for future work. Functions return
// plain structs; printing and files are lab_report / main's job (docs/LAB.md).
#include "library/motion_library.hpp"
#include "lookahead/motion_tree.hpp"
#include "lookahead/recording.hpp"
#include "lookahead/replay.hpp"
#include "lookahead/strategy.hpp"
#include "world/collision_world.hpp"
#include "world/scene.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace foresight::lab {

/// Spare time per frame and what it buys (docs/LAB.md, "spare-time model"):
///   spare_s(T)  = max(0, T - frame_cost_s)       time left in a frame of interval T after a fixed
///                                                 cost (rendering at the minimal frame rate)
///   budget(T)   = round(spare_s(T) * expansions_per_s)   expansions granted to grow() per frame
/// Deterministic: the replay counts expansions, never reads the clock.
struct SpareTimeModel {
  double frame_cost_s = 1.0 / 60.0;
  double expansions_per_s = 20000.0;

  double spare_s(double interval_s) const;
  int64_t expansions_per_frame(double interval_s) const;
};

struct LabOptions {
  std::string scene = "maze";
  bool quick = false;
  double frame_cost_s = 1.0 / 60.0;
  /// A 2005 PC (paper-sized trees: tens to hundreds of nodes).
  double paper_expansions_per_s = 20000.0;
  /// How long to time MotionTree::grow for today's rate.
  double rate_measure_s = 0.3;
  /// Where Fig. 10 is taken: this fraction of the eval recording's duration.
  double fig10_time_fraction = 0.5;
  /// Frame interval of the navigation runs (budget from the paper-rate model).
  double navigation_interval_s = 1.0 / 30.0;
  /// Tree settings shared by every experiment (strategy and depth are set per controller).
  MotionTreeConfig tree;
};

/// Fig. 9's frame intervals: 1/60 .. 1/10 s (quick: 1/30, 1/15, 1/10).
std::vector<double> lab_intervals(bool quick);

/// Everything one scene's experiments read. Keep it where it is: replays hold references.
struct LabScene {
  std::string name;
  Scene scene;
  CollisionWorld world;
  MotionLibrary library;
  Recording train;
  Recording eval;
};

/// The default library, the scene and data/recordings/<scene>_{train,eval}.json.
bool lab_load(const std::string& scene_name, LabScene& out, std::string& error);

/// A replay configuration for one frame interval and per-frame budget.
ReplayConfig lab_replay_config(const MotionTreeConfig& tree, double interval_s,
                               int64_t expansions_per_frame);

/// Statistics for strategies 3 and 4, learned on the training recording (command matching
/// controller, navigation budget).
TransitionStatistics lab_learn_statistics(const LabScene& lab, const LabOptions& options);

// ---- Today's expansion rate -----------------------------------------------------------------

struct RateMeasurement {
  double expansions_per_s = 0.0;
  int64_t expansions = 0;
  double seconds = 0.0;
  int trees = 0;  ///< Trees grown to full (pool or depth) during the measurement.
};

/// Times MotionTree::grow (command strategy, options.tree) from placements along the eval
/// recording's replayed path, regrowing each tree from its root until `options.rate_measure_s`.
RateMeasurement measure_expansion_rate(const LabScene& lab, const LabOptions& options);

// ---- Fig. 9 ---------------------------------------------------------------------------------

/// Average tree size over the replayed eval recording, per strategy and frame interval.
struct TreeSizeTable {
  SpareTimeModel model;
  std::vector<double> intervals_s;
  std::vector<int64_t> budgets;  ///< Expansions per frame, per interval.
  std::array<std::vector<double>, kNumStrategies> avg_tree_size;  ///< [strategy][interval]
};

/// One claim of the paper about Fig. 9 and whether this run agrees.
struct ShapeCheck {
  std::string claim;
  bool holds = false;
  std::string detail;
};

/// The paper's claims, checked over the intervals with a non-zero budget:
/// linear growth (R^2 of a least-squares line against spare time >= 0.95 per strategy),
/// type 0 smallest, 1 > 2, 3 largest, 4 between 1 and 3 (all on the mean over intervals).
std::vector<ShapeCheck> check_fig9_shape(const TreeSizeTable& table);

/// R^2 of the least-squares line y = a + b x (1 when y is constant).
double linear_r2(const std::vector<double>& x, const std::vector<double>& y);

TreeSizeTable run_tree_sizes(const LabScene& lab, const LabOptions& options,
                             const SpareTimeModel& model, const TransitionStatistics& statistics);

struct Fig9Result {
  TreeSizeTable paper;  ///< At options.paper_expansions_per_s.
  TreeSizeTable today;  ///< At the measured rate (trees capped by options.tree.max_nodes).
  RateMeasurement rate;
  std::vector<ShapeCheck> shape;  ///< On `paper`.
};

Fig9Result run_fig9(const LabScene& lab, const LabOptions& options,
                    const TransitionStatistics& statistics);

// ---- Fig. 10 --------------------------------------------------------------------------------

struct Fig10Panel {
  Strategy strategy = Strategy::kBreadthFirst;
  std::vector<vec2> end_positions_m;  ///< Every node's end position (root included, first).
  std::vector<int> depths;            ///< Per node, below the root.
  int max_depth = 0;
};

struct Fig10Result {
  double time_s = 0.0;  ///< Recording time of the snapshot.
  double interval_s = 0.0;
  int64_t expansions_per_frame = 0;
  Placement avatar;  ///< Where the avatar stands, per strategy (they may differ slightly).
  std::vector<Placement> avatars;
  vec2 command_world{0.0f};  ///< The command at that moment, as a world ground direction.
  std::vector<Fig10Panel> panels;  ///< Strategies 0..4.
};

/// Replays the eval recording with each strategy up to `fig10_time_fraction` of its duration
/// (navigation interval, paper-rate budget) and keeps the tree it holds then.
Fig10Result run_fig10(const LabScene& lab, const LabOptions& options,
                      const TransitionStatistics& statistics);

// ---- Navigation efficiency and responsiveness -----------------------------------------------

struct ControllerSpec {
  std::string name;  ///< "look-ahead 0 breadth-first", ..., "greedy depth-1", "naive FSM".
  MotionTreeConfig tree;
  bool lookahead = false;  ///< Look-ahead controllers must never collide.
};

/// Look-ahead with each strategy 0..4, then greedy depth-1, then the naive game FSM.
std::vector<ControllerSpec> lab_controllers(const MotionTreeConfig& base);

struct NavigationRow {
  std::string recording;   ///< "train" or "eval".
  std::string controller;
  bool lookahead = false;
  bool reached_goal = false;
  double time_to_goal_s = 0.0;  ///< Meaningful when reached_goal.
  double seconds = 0.0;         ///< Simulated seconds replayed.
  int fallbacks = 0;
  int64_t colliding_frames = 0;
  double mean_command_angle_deg = 0.0;
  double avg_tree_size = 0.0;
  double response_ms_p50 = 0.0;
  double response_ms_p95 = 0.0;
  size_t responses = 0;
};

struct ControllerSummary {
  std::string controller;
  bool lookahead = false;
  int goals_reached = 0;
  int recordings = 0;
  int fallbacks = 0;
  int64_t colliding_frames = 0;
  double response_ms_p50 = 0.0;  ///< Over both recordings' responses pooled.
  double response_ms_p95 = 0.0;
};

struct NavigationResult {
  double interval_s = 0.0;
  int64_t expansions_per_frame = 0;
  std::vector<NavigationRow> rows;
  std::vector<ControllerSummary> summary;  ///< In lab_controllers() order.
  int64_t lookahead_collisions = 0;        ///< Colliding frames over every look-ahead run.
  /// Recordings where the naive FSM did not reach the goal ...
  std::vector<std::string> naive_stuck;
  /// ... and whether every look-ahead controller reached it in each of them (true if none).
  bool lookahead_reached_where_naive_stuck = true;
  double response_target_ms = 350.0;
};

NavigationResult run_navigation(const LabScene& lab, const LabOptions& options,
                                const TransitionStatistics& statistics);

/// Percentile p in [0, 100] by linear interpolation between order statistics (0 when empty).
double percentile(std::vector<double> samples, double p);

// ---- Everything -----------------------------------------------------------------------------

struct LabResult {
  std::string scene;
  LabOptions options;
  Fig9Result fig9;
  Fig10Result fig10;
  NavigationResult navigation;
  double wall_s = 0.0;  ///< Time the whole run took.
};

/// Loads nothing: runs every experiment on a loaded scene.
LabResult run_lab(const LabScene& lab, const LabOptions& options);

}  // namespace foresight::lab

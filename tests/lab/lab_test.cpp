// The lab's experiments on quick settings: they run from the shipped data, the safety figures
// hold (no collisions; the recorder's own controller reaches every goal), and its statistics
// helpers compute what they say.
#include "lab/lab_experiments.hpp"

#include "lab/lab_report.hpp"
#include "support/test_paths.hpp"

#include <gtest/gtest.h>

namespace foresight::lab {
namespace {

TEST(LabStatistics, LinearFitAndPercentiles) {
  EXPECT_NEAR(linear_r2({1, 2, 3, 4}, {3, 5, 7, 9}), 1.0, 1e-12);
  EXPECT_LT(linear_r2({1, 2, 3, 4}, {1, 9, 1, 9}), 0.5);
  EXPECT_DOUBLE_EQ(percentile({}, 50), 0.0);
  EXPECT_DOUBLE_EQ(percentile({4, 1, 3, 2}, 0), 1.0);
  EXPECT_DOUBLE_EQ(percentile({4, 1, 3, 2}, 100), 4.0);
  EXPECT_DOUBLE_EQ(percentile({1, 2, 3}, 50), 2.0);
}

TEST(Lab, QuickRunOnObstaclesReproducesItsSafetyFigures) {
  LabScene scene;
  std::string error;
  ASSERT_TRUE(lab_load("obstacles", {}, scene, error)) << error;
  LabOptions options;
  options.scene = "obstacles";
  options.quick = true;
  options.today_rate = false;        // the slowest part, and machine dependent
  options.intervals_s = {1.0 / 20};  // one interval with a non-zero budget
  const LabResult r = run_lab(scene, options);
  ASSERT_TRUE(r.error.empty()) << r.error;
  // Recordings are open-loop key presses: they reproduce their run only with the library they
  // were made with. A library change must regenerate them (docs/RECORDINGS.md).
  EXPECT_TRUE(r.recordings_match_library);
  EXPECT_EQ(r.navigation.lookahead_collisions, 0);
  EXPECT_EQ(r.closed_loop.lookahead_collisions, 0);
  // The recorder's controller (look-ahead 1, command matching) reaches both goals in replay.
  bool found = false;
  for (const ControllerSummary& c : r.navigation.summary)
    if (c.controller == "look-ahead 1 command") {
      found = true;
      EXPECT_EQ(c.goals_reached, c.recordings);
      EXPECT_EQ(c.recordings, 2);
    }
  EXPECT_TRUE(found);
  // Fig. 9 at one interval: every strategy grew a tree; the paper's five claims were checked.
  for (int s = 0; s < kNumStrategies; ++s) {
    ASSERT_EQ(r.fig9.paper.avg_tree_size[static_cast<size_t>(s)].size(), 1u);
    EXPECT_GT(r.fig9.paper.avg_tree_size[static_cast<size_t>(s)][0], 10.0) << s;
  }
  EXPECT_EQ(r.fig9.shape.size(), 5u);
  EXPECT_EQ(r.fig10.panels.size(), static_cast<size_t>(kNumStrategies));
  // Motion quality rows: the paper's controller, steering raw, steering + pose stage (the
  // default), printed and in the JSON line with the keys.
  ASSERT_EQ(r.motion_quality.size(), 3u);
  EXPECT_FALSE(r.motion_quality[1].pose_stage);
  EXPECT_TRUE(r.motion_quality[2].pose_stage);
  EXPECT_GT(r.motion_quality[1].foot_skate_cm_per_s_p95, r.motion_quality[2].foot_skate_cm_per_s_p95);
  EXPECT_EQ(r.motion_quality[2].collisions, 0);
  EXPECT_NE(motion_quality_text(r.motion_quality).find("steering + pose stage"), std::string::npos);
  const std::string json = lab_json(r);
  EXPECT_NE(json.find("\"motion_quality\":[{"), std::string::npos);
  for (const char* key : {"\"foot_skate_cm_per_s_p95\"", "\"ground_error_cm_p95\"", "\"pops_per_min\"",
                          "\"limit_violations\"", "\"goals_reached_share\""})
    EXPECT_NE(json.find(key), std::string::npos) << key;
}

// The lab on a captured library (--motions): the closed-loop player steers the Bandai capture
// through the maze without a colliding frame, the responsive controller reaches the goal, and
// the JSON line carries the built-in library's figures beside the capture's.
TEST(Lab, QuickClosedLoopOnRealCaptureReachesTheGoalBesideTheBuiltInLibrary) {
  FORESIGHT_REQUIRE_MOCAP();
  MotionSource motions;
  motions.motions_dir = test::mocap_dir() / "locomotion";
  LabScene captured, builtin;
  std::string error;
  ASSERT_TRUE(lab_load("maze", motions, captured, error)) << error;
  ASSERT_TRUE(lab_load("maze", {}, builtin, error)) << error;
  // The closed loop only (one player seed per controller): the figures the capture is judged by.
  LabOptions options;
  options.quick = true;
  LabResult r;
  r.closed_loop = run_closed_loop_navigation(captured, options, lab_learn_statistics(captured, options));
  ASSERT_TRUE(r.closed_loop.error.empty()) << r.closed_loop.error;
  EXPECT_EQ(r.closed_loop.lookahead_collisions, 0);
  bool found = false;
  for (const ControllerSummary& c : r.closed_loop.summary)
    if (c.controller == kResponsiveController) {
      found = true;
      EXPECT_EQ(c.goals_reached, c.recordings);
    }
  EXPECT_TRUE(found);
  r.builtin_closed_loop = run_closed_loop_navigation(builtin, options, lab_learn_statistics(builtin, options));
  const std::string json = lab_json(r);
  for (const char* key : {"\"response_ms_p95\"", "\"response_goals_reached\"", "\"builtin_response_ms_p50\"",
                          "\"builtin_response_ms_p95\"", "\"builtin_response_goals_reached\""})
    EXPECT_NE(json.find(key), std::string::npos) << key;
}

}  // namespace
}  // namespace foresight::lab

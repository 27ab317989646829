#include "library/library_source.hpp"
#include "library_checks.hpp"
#include "support/test_paths.hpp"

#include <gtest/gtest.h>

#include <fstream>

namespace foresight {
namespace {

TEST(FolderLibrary, RealLocomotionCaptureGivesAStronglyConnectedGraph) {
  FORESIGHT_REQUIRE_MOCAP();
  MotionLibrary lib;
  AutoGraphReport report;
  std::string error;
  AutoGraphOptions options;
  options.candidate_stride = 3;  // keeps the sanitizer build fast; the bench uses the default
  ASSERT_TRUE(motion_library_from_folder(test::mocap_dir() / "locomotion", BvhImportOptions{},
                                         options, lib, &report, error))
      << error;
  std::printf("[          ] locomotion: %zu clips, %lld frame pairs, %d minima, %d transitions; "
              "graph %d segments / %d edges before pruning, %d / %d after\n",
              lib.clips.size(), report.frame_pairs_compared, report.local_minima,
              report.transitions_accepted, report.segments_before_prune, report.edges_before_prune,
              report.segments, report.edges);
  EXPECT_EQ(lib.clips.size(), 25u);
  EXPECT_GE(report.segments, 20);
  EXPECT_GT(report.edges, report.segments);  // more than a ring: there are real choices
  // Cross-clip transitions exist: the graph mixes takes, not only loops within one.
  int cross = 0;
  for (const Transition& t : lib.graph.transitions)
    cross += lib.graph.segments[t.from].clip != lib.graph.segments[t.to].clip;
  EXPECT_GT(cross, 10);
  // Captured motion through blended edges: joint jumps stay within a few frames' worth of motion.
  test::expect_continuous_edges(lib, 3.0f, 0.03f);
}

TEST(FolderLibrary, MissingFolderAndForeignSkeletonAreReported) {
  MotionLibrary lib;
  std::string error;
  EXPECT_FALSE(motion_library_from_folder("/nonexistent/motions", {}, {}, lib, nullptr, error));
  EXPECT_NE(error.find("/nonexistent/motions"), std::string::npos) << error;

  FORESIGHT_REQUIRE_MOCAP();
  const auto dir = test::scratch_dir();
  // A link, not a copy: the capture files stay where their licence allows them.
  std::filesystem::create_symlink(
      test::mocap_dir() / "locomotion" / "bandai_dataset-1_walk_normal_001.bvh", dir / "a.bvh");
  std::ofstream(dir / "b.bvh") << "HIERARCHY\nROOT Hips\n{\n OFFSET 0 0 0\n CHANNELS 3 Xposition "
                                  "Yposition Zposition\n End Site\n {\n  OFFSET 0 10 0\n }\n}\n"
                                  "MOTION\nFrames: 2\nFrame Time: 0.0333333\n0 90 0\n0 90 1\n";
  EXPECT_FALSE(motion_library_from_folder(dir, {}, {}, lib, nullptr, error));
  EXPECT_NE(error.find("b.bvh"), std::string::npos) << error;
  EXPECT_NE(error.find("skeleton differs"), std::string::npos) << error;
}

}  // namespace
}  // namespace foresight

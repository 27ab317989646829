#include "library_build/library_source.hpp"
#include "library/steerability.hpp"
#include "anim/canonical_skeleton.hpp"
#include "anim/fk.hpp"
#include "library_checks.hpp"
#include "support/bvh_variants.hpp"
#include "support/test_paths.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

namespace foresight {
namespace {

TEST(FolderLibrary, RealLocomotionCaptureGivesAStronglyConnectedGraph) {
  FORESIGHT_REQUIRE_MOCAP();
  MotionLibrary lib;
  LibraryImportReport imported;
  std::string error;
  MotionSource source;
  source.motions_dir = test::mocap_dir() / "locomotion";
  source.graph.candidate_stride = 3;  // keeps the sanitizer build fast; the bench uses the default
  ASSERT_TRUE(motion_library_from_folder(source, lib, &imported, error)) << error;
  const AutoGraphReport& report = imported.graph;
  std::printf("[          ] locomotion: %zu clips, %lld frame pairs, %d minima, %d transitions; "
              "graph %d segments / %d edges before pruning, %d / %d after\n",
              lib.clips.size(), report.frame_pairs_compared, report.local_minima,
              report.transitions_accepted, report.segments_before_prune, report.edges_before_prune,
              report.segments, report.edges);
  // Every take kept and joined (with derived stops and starts), none dropped.
  ASSERT_EQ(imported.files.size(), 25u);
  int captured = 0;
  for (const ClipInGraph& c : imported.clips) {
    if (c.derived) continue;
    ++captured;
    EXPECT_GT(c.segments_kept, 0) << c.clip << ": " << c.dropped_why;
  }
  EXPECT_EQ(captured, 25);
  EXPECT_GE(report.segments, 20);
  EXPECT_GT(report.edges, report.segments);  // more than a ring: there are real choices
  // Cross-clip transitions exist: the graph mixes takes, not only loops within one.
  int cross = 0;
  for (const Transition& t : lib.graph.transitions) {
    const int a = lib.graph.segments[t.from].clip, b = lib.graph.segments[t.to].clip;
    cross += a != b && a < captured && b < captured;
  }
  EXPECT_GT(cross, 10);
  // A player's every command can be followed, from standing and from walking (the derived idle,
  // turns on the spot, stops and starts: the capture has none of them).
  // What the Bandai takes have of it themselves (their README: no walk-to-stop, no turn in place).
  EXPECT_FALSE(imported.derived.captured_turn_on_spot);
  EXPECT_FALSE(imported.derived.captured_stop);
  EXPECT_TRUE(imported.derived.captured_start);  // dataset-2_walk_normal_001 starts from standstill
  EXPECT_EQ(imported.derived.idles, 1);
  EXPECT_EQ(imported.derived.turns, 6);
  EXPECT_GT(imported.derived.stops, 20);
  EXPECT_GT(imported.derived.starts, 5);
  for (int start : {standing_segment(lib), walking_segment(lib)}) {
    ASSERT_GE(start, 0);
    const auto can = followable_directions(lib, start);
    for (int k = 0; k < kCommandSectors; ++k)
      EXPECT_TRUE(can[static_cast<size_t>(k)]) << lib.graph.segments[static_cast<size_t>(start)].name << " cannot go "
                                               << command_sector_name(k);
  }
  // Turns on the spot keep a foot planted in every frame (the other steps round), and end on the
  // standing pose: both ankles where the turned standing pose has them.
  int turns = 0;
  std::vector<vec3> pos;
  for (const Clip& clip : lib.clips) {
    if (!clip.name.starts_with("derived_turn_")) continue;
    ++turns;
    fk_clip_positions(lib.skeleton, clip, pos);
    const int n = clip.num_joints;
    for (int f = 1; f < clip.num_frames; ++f) {
      float still = 1e9f;
      for (int ankle : {kCanonLeftFoot, kCanonRightFoot})
        still = std::min(still, glm::length(pos[static_cast<size_t>(f) * n + ankle] - pos[static_cast<size_t>(f - 1) * n + ankle]));
      EXPECT_LT(still, 0.002f) << clip.name << " frame " << f << ": no foot planted";
    }
  }
  EXPECT_EQ(turns, 6);
  // Captured motion through blended edges: joint jumps stay within a few frames' worth of motion.
  test::expect_continuous_edges(lib, 3.0f, 0.03f);
}

MotionSource folder(const std::filesystem::path& dir) {
  MotionSource source;
  source.motions_dir = dir;
  source.graph.candidate_stride = 3;
  return source;
}

TEST(FolderLibrary, AFileThatIsNoHumanoidIsSkippedWithItsReasonOrRefusedWhenStrict) {
  MotionLibrary lib;
  std::string error;
  EXPECT_FALSE(motion_library_from_folder(folder("/nonexistent/motions"), lib, nullptr, error));
  EXPECT_NE(error.find("/nonexistent/motions"), std::string::npos) << error;

  FORESIGHT_REQUIRE_MOCAP();
  const auto dir = test::scratch_dir();
  // Links, not copies: the capture files stay where their licence allows them.
  for (const char* take : {"bandai_dataset-2_walk_normal_001.bvh", "bandai_dataset-2_walk-turn-left_normal_001.bvh"})
    std::filesystem::create_symlink(test::mocap_dir() / "locomotion" / take, dir / take);
  std::ofstream(dir / "prop.bvh") << "HIERARCHY\nROOT Hips\n{\n OFFSET 0 0 0\n CHANNELS 3 Xposition "
                                     "Yposition Zposition\n End Site\n {\n  OFFSET 0 10 0\n }\n}\n"
                                     "MOTION\nFrames: 2\nFrame Time: 0.0333333\n0 90 0\n0 90 1\n";
  std::ofstream(dir / "truncated.bvh") << "HIERARCHY\nROOT Hips\n{\n OFFSET 0 0 0\n";
  LibraryImportReport report;
  ASSERT_TRUE(motion_library_from_folder(folder(dir), lib, &report, error)) << error;
  ASSERT_EQ(report.files.size(), 4u);
  for (const ClipImport& c : report.files) {
    const bool bad = c.file == "prop.bvh" || c.file == "truncated.bvh";
    EXPECT_EQ(c.kept, !bad) << c.file;
    if (bad) {
      EXPECT_NE(c.reason.find(c.file.substr(0, c.file.size() - 4)), std::string::npos) << c.reason;
    }
  }
  const auto prop = std::find_if(report.files.begin(), report.files.end(), [](const ClipImport& c) { return c.file == "prop.bvh"; });
  ASSERT_NE(prop, report.files.end());
  EXPECT_NE(prop->reason.find("not a humanoid"), std::string::npos) << prop->reason;

  MotionSource strict = folder(dir);
  strict.strict = true;
  EXPECT_FALSE(motion_library_from_folder(strict, lib, nullptr, error));
  EXPECT_NE(error.find("--strict"), std::string::npos) << error;
}

// One folder, one take written five ways (another unit, other names, an extra dummy root, other
// Euler orders, 60 fps, fingers and twist bones) plus another actor's takes: every file is kept,
// every clip plays on one body, and the automatic graph joins the variants.
TEST(FolderLibrary, CapturesOfDifferentSkeletonsMixInOneFolder) {
  FORESIGHT_REQUIRE_MOCAP();
  const auto dir = test::scratch_dir();
  BvhDocument take;
  std::string error;
  ASSERT_TRUE(bvh_load(test::mocap_dir() / "locomotion" / "bandai_dataset-2_walk_normal_002.bvh", take, error)) << error;
  std::filesystem::create_symlink(test::mocap_dir() / "locomotion" / "bandai_dataset-1_walk_normal_001.bvh",
                                  dir / "other_actor.bvh");
  BvhDocument inches = take;
  test::scale_document(inches, 1.0f / 2.54f);
  BvhDocument renamed = take;
  for (BvhJoint& j : renamed.joints) j.name = "mixamorig:" + j.name;
  test::insert_parent(renamed, 0, "Reference", 0.0f);
  BvhDocument reordered = take;
  test::reorder_rotations(reordered, "XYZ");
  test::upsample(reordered, 2);
  BvhDocument fingers = take;
  test::add_fingers(fingers, "Hand_L", 1.0f);
  test::add_fingers(fingers, "Hand_R", -1.0f);
  test::insert_parent(fingers, test::joint_named(fingers, "LowerArm_L"), "UpperArmTwist_L", 0.5f);
  const std::pair<const char*, const BvhDocument*> files[] = {
      {"a_centimetres.bvh", &take}, {"b_inches.bvh", &inches}, {"c_renamed.bvh", &renamed},
      {"d_xyz_60fps.bvh", &reordered}, {"e_fingers.bvh", &fingers}};
  for (const auto& [name, doc] : files) ASSERT_TRUE(bvh_save(dir / name, *doc, error)) << error;

  MotionLibrary lib;
  LibraryImportReport report;
  ASSERT_TRUE(motion_library_from_folder(folder(dir), lib, &report, error)) << error;
  ASSERT_EQ(report.files.size(), 6u);
  for (const ClipImport& c : report.files) {
    EXPECT_TRUE(c.kept) << c.file << ": " << c.reason;
    EXPECT_NEAR(c.import.standing_height_m, kCanonicalStandingHeightM, 0.01f) << c.file;
    EXPECT_LT(std::fabs(c.import.lowest_foot_m), 0.1f) << c.file;
  }
  EXPECT_EQ(lib.skeleton.num_joints(), kCanonJointCount);
  for (const Clip& c : lib.clips) EXPECT_FLOAT_EQ(c.fps, 30.0f) << c.name;
  // The variants of one take are one motion: the graph joins them (cross-clip transitions), and
  // every clip has a place in it.
  int cross = 0;
  for (const Transition& t : lib.graph.transitions) {
    const int a = lib.graph.segments[t.from].clip, b = lib.graph.segments[t.to].clip;
    cross += a != b && a < 6 && b < 6;  // between captured clips, not through derived stops
  }
  EXPECT_GT(cross, 5);
  for (const ClipInGraph& c : report.clips) {
    if (!c.derived) {
      EXPECT_GT(c.segments_kept, 0) << c.clip << ": " << c.dropped_why;
    }
  }
}

// The built-in library written out as BVH files and brought back as if it were a studio's
// capture: every clip kept, the crouching ones found crouching by their pelvis height alone (the
// automatic graph knows no names), and every command direction followable.
TEST(FolderLibrary, TheBuiltInLibraryExportedAsCaptureComesBackCrouchingWhereItCrouches) {
  const MotionLibrary built_in = motion_library_default();
  const auto dir = test::scratch_dir();
  std::string error;
  for (const Clip& clip : built_in.clips)
    ASSERT_TRUE(bvh_save(dir / (clip.name + ".bvh"), bvh_from_clip(built_in.skeleton, clip), error)) << error;
  MotionLibrary lib;
  LibraryImportReport report;
  ASSERT_TRUE(motion_library_from_folder(folder(dir), lib, &report, error)) << error;
  for (const ClipImport& f : report.files) EXPECT_TRUE(f.kept) << f.file << ": " << f.reason;
  // The built-in library has all a player's commands need, and the detection sees it.
  EXPECT_TRUE(report.derived.captured_idle);
  EXPECT_TRUE(report.derived.captured_turn_on_spot);
  EXPECT_TRUE(report.derived.captured_stop);
  EXPECT_TRUE(report.derived.captured_start);
  // Crouch-walks and crouched idles are found crouching, walks, runs and the idle are not (the
  // transitions between the two, crouch_down and the like, may go either way).
  int crouch_clips = 0, upright_clips = 0;
  for (size_t c = 0; c < lib.clips.size(); ++c) {
    const std::string& name = lib.clips[c].name;
    const bool crouched = (lib.clip_tags[c] & kTagCrouch) != 0;
    if (name.starts_with("crouch_walk_l") || name.starts_with("crouch_walk_r") || name.starts_with("crouch_walk_turn") ||
        name.starts_with("crouch_idle")) {
      EXPECT_TRUE(crouched) << name;
      ++crouch_clips;
    } else if (name.starts_with("walk_") || name.starts_with("run_") || name == "idle") {
      EXPECT_FALSE(crouched) << name;
      ++upright_clips;
    }
  }
  EXPECT_GE(upright_clips, 10);
  EXPECT_GE(crouch_clips, 4);
  for (int start : {standing_segment(lib), walking_segment(lib)}) {
    ASSERT_GE(start, 0);
    const auto can = followable_directions(lib, start);
    for (int k = 0; k < kCommandSectors; ++k) EXPECT_TRUE(can[static_cast<size_t>(k)]) << command_sector_name(k);
  }
}

}  // namespace
}  // namespace foresight

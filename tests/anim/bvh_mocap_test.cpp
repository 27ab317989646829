// The real captures in ../shared/mocap (Bandai-Namco, centimetres, Y up, 30 fps, a static
// `joint_Root` above `Hips`): every file must import to a standing, plausibly sized character.
// Skipped with a message when the folder is absent.
#include "import/bvh_import.hpp"
#include "anim/root_motion.hpp"
#include "bvh_test_util.hpp"
#include "support/test_paths.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>

namespace foresight {
namespace {

std::vector<std::filesystem::path> mocap_files() {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::recursive_directory_iterator(test::mocap_dir()))
    if (e.is_regular_file() && e.path().extension() == ".bvh") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

bool is_foot(const std::string& name) {
  return name.find("Foot") != std::string::npos || name.find("Toe") != std::string::npos;
}

TEST(BvhMocap, EveryFileImportsAsAStandingThirtyFpsCharacter) {
  FORESIGHT_REQUIRE_MOCAP();
  const auto files = mocap_files();
  ASSERT_FALSE(files.empty()) << "no .bvh under " << test::mocap_dir();
  std::cout << "[ mocap    ] " << files.size() << " BVH files under " << test::mocap_dir()
            << "\n";
  for (const auto& path : files) {
    SCOPED_TRACE(path.string());
    Skeleton skeleton;
    Clip clip;
    BvhImportReport report;
    std::string error;
    ASSERT_TRUE(clip_load_bvh(path, {}, skeleton, clip, &report, error)) << error;
    EXPECT_TRUE(skeleton.valid());
    EXPECT_EQ(clip.name, path.stem().string());
    EXPECT_EQ(report.unit, LengthUnit::kCentimetres) << "body size " << report.body_size;
    EXPECT_EQ(report.up, UpAxis::kYUp);
    EXPECT_EQ(clip.fps, 30.0f);
    EXPECT_NEAR(report.source_fps, 30.0f, 0.01f);
    EXPECT_EQ(clip.num_frames, report.source_frames);  // 30 fps: copied, not resampled
    EXPECT_EQ(report.folded_root_joints, 1);
    EXPECT_EQ(skeleton.joint_names[0], "Hips");
    EXPECT_EQ(skeleton.find_joint("joint_Root"), -1);
    const std::vector<vec3> pos = test::clip_positions(skeleton, clip);
    const float hips_y = pos[0].y;
    float lowest_foot = 1e9f, highest_foot = -1e9f;
    int feet = 0;
    for (int j = 0; j < skeleton.num_joints(); ++j) {
      if (!is_foot(skeleton.joint_names[j])) continue;
      feet += !skeleton.is_end_site[j];
      lowest_foot = std::min(lowest_foot, pos[j].y);
      highest_foot = std::max(highest_foot, pos[j].y);
    }
    std::printf("[ mocap    ] %-46s hips %.3f m, feet %.3f..%.3f m, body %.0f cm, %d frames\n",
                path.filename().string().c_str(), hips_y, lowest_foot, highest_foot,
                report.body_size, clip.num_frames);
    // Standing or moving upright on a floor at y = 0, scaled to the canonical 1.725 m (x1.05 for
    // this actor). Sprint/run clips start mid-stride: the hips are lower (0.83 m in
    // dash_masculinity) and the swing foot can be 0.47 m up, so the 0.25 m bound applies to the
    // supporting (lowest) foot.
    EXPECT_GE(hips_y, 0.78f);
    EXPECT_LE(hips_y, 1.05f);
    EXPECT_EQ(feet, 4);  // Foot_L/R, Toes_L/R (their End Sites are checked too)
    EXPECT_GT(lowest_foot, -0.05f);
    EXPECT_LT(lowest_foot, 0.25f);
    EXPECT_LT(highest_foot, 0.55f);
    const int head = skeleton.find_joint("Head");
    ASSERT_GE(head, 0);
    EXPECT_GT(pos[head].y, hips_y + 0.3f);
  }
}

TEST(BvhMocap, StraightWalkCoversAPlausibleDistanceAlongPlusZ) {
  FORESIGHT_REQUIRE_MOCAP();
  struct Walk {
    const char* file;
    float min_m, max_m;
  } walks[] = {{"locomotion/bandai_dataset-2_walk_normal_001.bvh", 8.5f, 11.5f},
               {"locomotion/bandai_dataset-1_walk_normal_001.bvh", 6.5f, 9.5f}};
  for (const Walk& w : walks) {
    SCOPED_TRACE(w.file);
    Skeleton skeleton;
    Clip clip;
    std::string error;
    ASSERT_TRUE(clip_load_bvh(test::mocap_dir() / w.file, {}, skeleton, clip, nullptr, error))
        << error;
    const vec3 start = clip.frame_pos(0)[0], end = clip.frame_pos(clip.num_frames - 1)[0];
    const vec2 moved = ground(end) - ground(start);
    const float dist = glm::length(moved);
    EXPECT_GT(dist, w.min_m);
    EXPECT_LT(dist, w.max_m);
    const float speed = dist / clip.duration_s();
    EXPECT_GT(speed, 0.7f);
    EXPECT_LT(speed, 1.8f);
    // Walks head roughly along +Z, and the character faces where it goes with its left on +X.
    EXPECT_GT(moved.y, 0.8f * dist);
    const LeftRightPair lr = find_left_right_pair(skeleton);
    ASSERT_GE(lr.left, 0);
    const std::vector<vec3> pos = test::clip_positions(skeleton, clip);
    EXPECT_GT(pos[lr.left].x, pos[lr.right].x);
  }
}

TEST(BvhMocap, RealFileRoundTripsThroughTheWriter) {
  FORESIGHT_REQUIRE_MOCAP();
  const auto path = test::mocap_dir() / "fighting/bandai_dataset-1_kick_normal_001.bvh";
  BvhDocument doc, again;
  std::string error;
  ASSERT_TRUE(bvh_load(path, doc, error)) << error;
  EXPECT_EQ(doc.joints.size(), 22u + 5u);  // 22 joints + 5 End Sites
  EXPECT_EQ(doc.num_channels(), 132);
  ASSERT_TRUE(bvh_parse(bvh_write(doc), "written", again, error)) << error;
  EXPECT_EQ(again.values, doc.values);

  // Normalised clip -> BVH (metres, ZXY) -> clip: same joint positions.
  Skeleton skeleton, s2;
  Clip clip, c2;
  ASSERT_TRUE(clip_from_bvh(doc, "kick", {}, skeleton, clip, nullptr, error)) << error;
  const BvhDocument out = bvh_from_clip(skeleton, clip);
  ASSERT_TRUE(bvh_parse(bvh_write(out), "out", again, error)) << error;
  BvhImportReport report;
  ASSERT_TRUE(clip_from_bvh(again, "kick2", {}, s2, c2, &report, error)) << error;
  EXPECT_EQ(report.unit, LengthUnit::kMetres);
  EXPECT_EQ(report.up, UpAxis::kYUp);
  test::expect_near_positions(test::clip_positions(s2, c2), test::clip_positions(skeleton, clip),
                              1e-4f);
}

}  // namespace
}  // namespace foresight

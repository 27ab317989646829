// Building the fighter database (fighter_database.hpp): from the default library, from BVH folders
// with and without a sidecar, and the synthetic benchmark database.
#include "author/default_library.hpp"
#include "fighter_build/fighter_database_build.hpp"
#include "import/bvh.hpp"
#include "import/bvh_import.hpp"
#include "fighter/fighter_database.hpp"
#include "support/test_paths.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <map>

namespace foresight {
namespace {

const std::filesystem::path kBandaiSidecar = std::filesystem::path(FORESIGHT_DATA_DIR) / "fighter" / "bandai_fighting.strikes.json";

FighterDatabase default_db() {
  FighterDatabase db;
  std::string error;
  EXPECT_TRUE(fighter_database_add_default_library(db, error)) << error;
  return db;
}

void expect_consistent(const FighterDatabase& db, bool synthetic = false) {
  for (const FighterEntry& e : db.entries) {
    SCOPED_TRACE(e.name);
    ASSERT_GE(e.take, 0);
    ASSERT_LT(e.take, static_cast<int>(db.takes.size()));
    const FighterTake& t = db.takes[static_cast<std::size_t>(e.take)];
    EXPECT_LE(e.start_frame, e.hit_frame);
    EXPECT_LE(e.hit_frame, e.end_frame);
    EXPECT_LT(e.end_frame, t.clip.num_frames);
    EXPECT_EQ(e.key_points.size(), static_cast<std::size_t>(e.num_frames()) * kPoseKeyPoints);
    EXPECT_EQ(e.hit_path_m.size(), static_cast<std::size_t>(e.num_frames()));
    EXPECT_EQ(e.root_from_start_m.size(), static_cast<std::size_t>(e.num_frames()));
    if (!synthetic) {
      EXPECT_FLOAT_EQ(e.body_size_m, t.rig.body_size_m);
    }
    // The path starts at the start frame's root frame: the first placement is the identity.
    EXPECT_NEAR(e.root_from_start_m[0].pos_m.x, 0.0f, 1e-4f);
    EXPECT_NEAR(e.root_from_start_m[0].heading_rad, 0.0f, 1e-4f);
    for (const vec3& p : e.hit_path_m) {
      EXPECT_TRUE(glm::all(glm::lessThanEqual(e.hit_box_min_m, p)));
      EXPECT_TRUE(glm::all(glm::lessThanEqual(p, e.hit_box_max_m)));
    }
  }
}

TEST(FighterDatabase, HoldsTheDefaultStrikesWithTheirAnnotations) {
  const FighterDatabase db = default_db();
  ASSERT_EQ(db.entries.size(), 16u);  // per side 4 punches and 4 kicks
  expect_consistent(db);
  int kicks = 0, rights = 0;
  for (const FighterEntry& e : db.entries) {
    kicks += e.kind == StrikeKind::kKick;
    rights += e.side == StrikeSide::kRight;
    const FighterTake& t = db.takes[static_cast<std::size_t>(e.take)];
    const std::string joint = t.skeleton.joint_names[static_cast<std::size_t>(e.hit_joint)];
    EXPECT_EQ(joint, std::string(e.side == StrikeSide::kLeft ? "Left" : "Right") +
                         (e.kind == StrikeKind::kKick ? "Foot" : "Hand"));
    // The hit point in front of the fighter at the annotated height (default_library.hpp ranges).
    const vec3 hit = e.hit_point_m();
    EXPECT_GT(hit.z, 0.2f) << e.name;
    if (e.height == StrikeHeight::kLow) {
      EXPECT_LT(hit.y, 0.85f) << e.name;
    }
    if (e.height == StrikeHeight::kHigh) {
      EXPECT_GT(hit.y, 1.45f) << e.name;
    }
  }
  EXPECT_EQ(kicks, 8);
  EXPECT_EQ(rights, 8);
}

TEST(FighterDatabase, HeightFromTheHitPointAgreesWithTheAuthoredHeights) {
  // The thresholds of strike_height_from_hit are calibrated on the authored strikes: the class
  // computed from each hit point must be the class its author gave.
  const FighterDatabase db = default_db();
  // The floor the loader measures: the lowest ankle, which a kick's path starts from.
  float floor_y = 1.0f;
  for (const FighterEntry& e : db.entries)
    if (e.kind == StrikeKind::kKick) floor_y = std::min(floor_y, e.hit_box_min_m.y);
  ASSERT_LT(floor_y, 0.2f);
  for (const FighterEntry& e : db.entries)
    EXPECT_EQ(strike_height_from_hit(e.hit_point_m().y - floor_y, e.body_size_m), e.height) << e.name;
}

TEST(FighterDatabase, LoadsTheMocapFolderWithTheShippedSidecar) {
  FORESIGHT_REQUIRE_MOCAP();
  FighterDatabase db;
  FolderLoadReport report;
  std::string error;
  ASSERT_TRUE(fighter_database_add_folder(db, test::mocap_dir() / "fighting", kBandaiSidecar, StrikeSplitParams{},
                                          &report, error))
      << error;
  EXPECT_EQ(report.takes_loaded, 3);
  EXPECT_EQ(report.takes_skipped, 2);  // the sword cuts
  EXPECT_EQ(report.strikes_annotated, 13);
  EXPECT_EQ(report.strikes_detected, 0);
  ASSERT_EQ(db.entries.size(), 13u);
  expect_consistent(db);
  int kicks = 0;
  for (const FighterEntry& e : db.entries) {
    kicks += e.kind == StrikeKind::kKick;
    EXPECT_EQ(e.name.find("slash"), std::string::npos);
  }
  EXPECT_EQ(kicks, 3);
}

TEST(FighterDatabase, SplitsAFolderWithoutSidecarAndSavesWhatItFound) {
  FORESIGHT_REQUIRE_MOCAP();
  FighterDatabase db;
  FolderLoadReport report;
  std::string error;
  // The mocap folder has no strikes.json: every take is split automatically.
  ASSERT_TRUE(fighter_database_add_folder(db, test::mocap_dir() / "fighting", {}, StrikeSplitParams{}, &report, error))
      << error;
  EXPECT_TRUE(report.sidecar.empty());
  EXPECT_EQ(report.takes_loaded, 5);
  expect_consistent(db);
  std::map<std::string, int> per_take;
  for (const FighterEntry& e : db.entries) ++per_take[db.takes[static_cast<std::size_t>(e.take)].name];
  EXPECT_EQ(per_take["bandai_dataset-1_punch_normal_001"], 5);
  EXPECT_EQ(per_take["bandai_dataset-1_punch_normal_002"], 5);
  EXPECT_EQ(per_take["bandai_dataset-1_kick_normal_001"], 3);

  // Save the detection as a sidecar, load the folder with it: the same entries.
  StrikeSidecar sidecar;
  for (int t = 0; t < static_cast<int>(db.takes.size()); ++t) sidecar.clips.push_back(fighter_database_marks(db, t));
  const std::filesystem::path path = test::scratch_dir() / "strikes.json";
  ASSERT_TRUE(strike_sidecar_save(path, sidecar, error)) << error;
  FighterDatabase again;
  ASSERT_TRUE(fighter_database_add_folder(again, test::mocap_dir() / "fighting", path, StrikeSplitParams{}, &report, error))
      << error;
  EXPECT_EQ(report.strikes_detected, 0);
  ASSERT_EQ(again.entries.size(), db.entries.size());
  for (std::size_t i = 0; i < db.entries.size(); ++i) {
    EXPECT_EQ(again.entries[i].start_frame, db.entries[i].start_frame);
    EXPECT_EQ(again.entries[i].hit_frame, db.entries[i].hit_frame);
    EXPECT_EQ(again.entries[i].end_frame, db.entries[i].end_frame);
    EXPECT_EQ(again.entries[i].height, db.entries[i].height);
  }
}

// A capture whose joints are named nothing a person would recognise (j0, j7, ...) supplies the
// same strikes: the takes land on the canonical skeleton, where automatic splitting finds what it
// finds on the original names. (A sidecar names the joints of the files it annotates.)
TEST(FighterDatabase, TakesOfAnyNamingSupplyTheSameStrikes) {
  FORESIGHT_REQUIRE_MOCAP();
  const std::filesystem::path dir = test::scratch_dir();
  for (const auto& entry : std::filesystem::directory_iterator(test::mocap_dir() / "fighting")) {
    if (entry.path().extension() != ".bvh") continue;
    BvhDocument doc;
    std::string error;
    ASSERT_TRUE(bvh_load(entry.path(), doc, error)) << error;
    for (size_t j = 0; j < doc.joints.size(); ++j) doc.joints[j].name = "j" + std::to_string(j * 7 % 23);
    ASSERT_TRUE(bvh_save(dir / entry.path().filename(), doc, error)) << error;
  }
  FighterDatabase original, renamed;
  FolderLoadReport a, b;
  std::string error;
  ASSERT_TRUE(fighter_database_add_folder(original, test::mocap_dir() / "fighting", {}, StrikeSplitParams{}, &a, error)) << error;
  ASSERT_TRUE(fighter_database_add_folder(renamed, dir, {}, StrikeSplitParams{}, &b, error)) << error;
  EXPECT_EQ(b.takes_loaded, a.takes_loaded);
  ASSERT_EQ(renamed.entries.size(), original.entries.size());
  ASSERT_GE(renamed.entries.size(), 13u);
  for (std::size_t i = 0; i < original.entries.size(); ++i) {
    EXPECT_EQ(renamed.entries[i].kind, original.entries[i].kind);
    EXPECT_EQ(renamed.entries[i].hit_frame, original.entries[i].hit_frame);
    EXPECT_EQ(renamed.entries[i].hit_joint, original.entries[i].hit_joint);
  }
  expect_consistent(renamed);
}

TEST(FighterDatabase, ABrokenSidecarStopsTheLoadWithItsNameAndField) {
  FORESIGHT_REQUIRE_MOCAP();
  const std::filesystem::path path = test::scratch_dir() / "strikes.json";
  std::ofstream(path) << R"({"format": "foresight-strikes", "version": 1, "clips": {
    "bandai_dataset-1_punch_normal_001.bvh": {"strikes": [
      {"hit_joint": "Hand_L", "kind": "punch", "side": "left", "hit_frame": 9000}]}}})";
  FighterDatabase db;
  std::string error;
  EXPECT_FALSE(fighter_database_add_folder(db, test::mocap_dir() / "fighting", path, StrikeSplitParams{}, nullptr, error));
  EXPECT_NE(error.find(path.string()), std::string::npos) << error;
  EXPECT_NE(error.find("strikes[0].hit_frame: 9000 is out of range"), std::string::npos) << error;
}

TEST(FighterDatabase, APerClipSidecarWinsOverTheFolderOne) {
  // A folder of our own: two default strikes written as BVH.
  const std::filesystem::path dir = test::scratch_dir();
  author::DefaultLibrarySpec lib = author::build_default_library();
  std::string error;
  int written = 0;
  for (const author::AuthoredClip& c : lib.clips) {
    if (!c.strike || (c.clip.name != "punch_left_jab_mid" && c.clip.name != "kick_right_front_mid")) continue;
    ASSERT_TRUE(bvh_save(dir / (c.clip.name + ".bvh"), bvh_from_clip(lib.skeleton, c.clip), error)) << error;
    ++written;
  }
  ASSERT_EQ(written, 2);
  std::ofstream(dir / "strikes.json") << R"({"format": "foresight-strikes", "version": 1, "clips": {
    "punch_left_jab_mid.bvh": {"skip": true},
    "kick_right_front_mid.bvh": {"strikes": [{"hit_joint": "RightFoot", "kind": "kick", "side": "right", "hit_frame": 18}]}}})";
  // The per-clip file brings the punch back, with its own hit frame.
  std::ofstream(dir / "punch_left_jab_mid.strikes.json") << R"({"format": "foresight-strikes", "version": 1,
    "strikes": [{"hit_joint": "LeftHand", "kind": "punch", "side": "left", "height": "mid", "hit_frame": 7}]})";
  FighterDatabase db;
  FolderLoadReport report;
  ASSERT_TRUE(fighter_database_add_folder(db, dir, {}, StrikeSplitParams{}, &report, error)) << error;
  EXPECT_EQ(report.takes_loaded, 2);
  EXPECT_EQ(report.takes_skipped, 0);
  ASSERT_EQ(db.entries.size(), 2u);
  expect_consistent(db);
  EXPECT_EQ(db.entries[0].kind, StrikeKind::kKick);
  EXPECT_EQ(db.entries[1].kind, StrikeKind::kPunch);
  EXPECT_EQ(db.entries[1].hit_frame, 7);
  EXPECT_EQ(db.entries[1].height, StrikeHeight::kMid);
}

TEST(FighterDatabase, SyntheticDatabaseIsDeterministicAndWellFormed) {
  const FighterDatabase seed = default_db();
  const FighterDatabase a = fighter_database_synthetic(seed, 500, 7);
  const FighterDatabase b = fighter_database_synthetic(seed, 500, 7);
  const FighterDatabase c = fighter_database_synthetic(seed, 500, 8);
  ASSERT_EQ(a.entries.size(), 500u);
  expect_consistent(a, true);
  bool differs_from_other_seed = false;
  for (std::size_t i = 0; i < a.entries.size(); ++i) {
    EXPECT_EQ(a.entries[i].key_points, b.entries[i].key_points);
    EXPECT_EQ(a.entries[i].hit_path_m, b.entries[i].hit_path_m);
    EXPECT_EQ(a.entries[i].start_frame, b.entries[i].start_frame);
    differs_from_other_seed = differs_from_other_seed || a.entries[i].hit_path_m != c.entries[i].hit_path_m;
  }
  EXPECT_TRUE(differs_from_other_seed);
}

}  // namespace
}  // namespace foresight

// End to end on real capture: the database built from ../shared/mocap/fighting (with the shipped
// sidecar) plus the default strikes, clustered through the disk cache, queried with a pose built
// from a skeleton, its rig, global joint positions and a root placement.
#include "anim/fk.hpp"
#include "fighter_build/retrieval_index.hpp"
#include "fighter_build/fighter_database_build.hpp"
#include "anim/root_motion.hpp"
#include "fighter/retrieval.hpp"
#include "support/test_paths.hpp"

#include <gtest/gtest.h>

namespace foresight {
namespace {

const std::filesystem::path kBandaiSidecar = std::filesystem::path(FORESIGHT_DATA_DIR) / "fighter" / "bandai_fighting.strikes.json";

TEST(RetrievalMocap, TheMocapDatabaseWorksEndToEnd) {
  FORESIGHT_REQUIRE_MOCAP();
  FighterDatabase db;
  std::string error;
  ASSERT_TRUE(fighter_database_add_default_library(db, error)) << error;
  const int num_default = static_cast<int>(db.entries.size());
  ASSERT_TRUE(fighter_database_add_folder(db, test::mocap_dir() / "fighting", kBandaiSidecar, StrikeSplitParams{}, nullptr,
                                          error))
      << error;
  ASSERT_EQ(db.entries.size(), static_cast<std::size_t>(num_default + 13));

  const std::filesystem::path cache = test::scratch_dir();
  FighterRetrievalIndex index;
  ClusterCacheStatus status{};
  fighter_retrieval_prepare(db, PoseClusterParams{}, RetrievalIndexParams{}, cache, index, &status, nullptr);
  EXPECT_EQ(status, ClusterCacheStatus::kMissBuilt);
  fighter_retrieval_prepare(db, PoseClusterParams{}, RetrievalIndexParams{}, cache, index, &status, nullptr);
  EXPECT_EQ(status, ClusterCacheStatus::kHit);
  FighterRetriever retriever(index);

  // A Bandai fighter at the start of its second right punch, posed from the take itself: key
  // points from FK of that frame and the frame's root placement.
  const int entry_index = num_default + 3 + 5 + 1;  // kicks (3), left punches (5), then right punches
  const FighterEntry& punch = db.entries[static_cast<std::size_t>(entry_index)];
  ASSERT_EQ(punch.kind, StrikeKind::kPunch);
  ASSERT_EQ(punch.side, StrikeSide::kRight);
  const FighterTake& take = db.takes[static_cast<std::size_t>(punch.take)];
  std::vector<vec3> global(static_cast<std::size_t>(take.clip.num_joints));
  std::vector<quat> global_rot(static_cast<std::size_t>(take.clip.num_joints));
  fk_pose(take.skeleton, take.clip.frame_pos(punch.start_frame), take.clip.frame_rot(punch.start_frame), global, global_rot);
  std::vector<Placement> track;
  extract_root_track(take.clip, find_forward_axis(take.skeleton, take.clip), track);
  RetrievalQuery q;
  fighter_key_points_m(take.rig, global, track[static_cast<std::size_t>(punch.start_frame)], q.pose_key_points_m);
  for (int i = 0; i < kPoseKeyPoints; ++i)  // the helper gives what the database stored
    EXPECT_NEAR(glm::length(q.pose_key_points_m[static_cast<std::size_t>(i)] / take.rig.body_size_m -
                            punch.key_points[static_cast<std::size_t>(i)]),
                0.0f, 1e-5f);
  q.body_size_m = take.rig.body_size_m;
  q.target_m = punch.hit_point_m();
  q.kind = StrikeKind::kPunch;
  q.side = StrikeSide::kRight;
  RetrievalResult r;
  ASSERT_TRUE(retriever.retrieve(q, RetrievalParams{}, r));
  const FighterEntry& got = db.entries[static_cast<std::size_t>(r.entry)];
  // A captured punch from the captured stance: a Bandai take, landing within 3 cm.
  EXPECT_NE(db.takes[static_cast<std::size_t>(got.take)].source, "default library") << got.name;
  EXPECT_LT(r.target_distance * q.body_size_m, 0.03f) << got.name;
  EXPECT_LT(r.pose_distance, 0.05f) << got.name;

  // The same stance ordered to kick high and right: a right kick, from the capture or not.
  q.kind = StrikeKind::kKick;
  q.target_m = vec3(-0.1f, 1.0f, 0.7f);
  ASSERT_TRUE(retriever.retrieve(q, RetrievalParams{}, r));
  EXPECT_EQ(db.entries[static_cast<std::size_t>(r.entry)].kind, StrikeKind::kKick);
  EXPECT_EQ(db.entries[static_cast<std::size_t>(r.entry)].side, StrikeSide::kRight);
  EXPECT_TRUE(std::isfinite(r.cost));
}

}  // namespace
}  // namespace foresight

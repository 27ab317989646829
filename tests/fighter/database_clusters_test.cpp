// The aligned pose distance (pose_cloud.hpp) and the cached k-means (pose_clusters.hpp).
#include "fighter/fighter_database.hpp"
#include "fighter_build/fighter_database_build.hpp"
#include "fighter_build/pose_clusters.hpp"
#include "support/test_paths.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <set>

namespace foresight {
namespace {

FighterDatabase default_db() {
  FighterDatabase db;
  std::string error;
  EXPECT_TRUE(fighter_database_add_default_library(db, error)) << error;
  return db;
}

std::array<vec3, kPoseKeyPoints> entry_pose(const FighterEntry& e, int frame_offset) {
  std::array<vec3, kPoseKeyPoints> p;
  for (int i = 0; i < kPoseKeyPoints; ++i)
    p[static_cast<std::size_t>(i)] = e.key_points[static_cast<std::size_t>(frame_offset * kPoseKeyPoints + i)];
  return p;
}

TEST(PoseCloud, AlignedDistanceIgnoresHeadingAndGroundPosition) {
  const FighterDatabase db = default_db();
  const std::array<vec3, kPoseKeyPoints> a = entry_pose(db.entries[3], 5);
  const Placement moved{vec2(0.7f, -1.3f), radians(75.0f)};
  std::array<vec3, kPoseKeyPoints> b;
  for (std::size_t i = 0; i < b.size(); ++i) b[i] = moved.apply(a[i]);
  Placement b_to_a;
  EXPECT_NEAR(pose_points_distance_sq(a, b, &b_to_a), 0.0f, 1e-5f);
  // The alignment undoes the move.
  for (std::size_t i = 0; i < b.size(); ++i) {
    const vec3 back = b_to_a.apply(b[i]);
    EXPECT_NEAR(glm::length(back - a[i]), 0.0f, 1e-4f) << i;
  }
  EXPECT_NEAR(wrap_angle(b_to_a.heading_rad + radians(75.0f)), 0.0f, 1e-4f);
}

TEST(PoseCloud, AlignedDistanceSeesHeightAndShapeChanges) {
  const FighterDatabase db = default_db();
  const std::array<vec3, kPoseKeyPoints> a = entry_pose(db.entries[0], 0);
  std::array<vec3, kPoseKeyPoints> b = a;
  for (vec3& p : b) p.y += 0.1f;  // a vertical shift is not aligned away
  EXPECT_NEAR(pose_points_distance_sq(a, b, nullptr), kPoseKeyPoints * 0.01f, 1e-4f);
  // Different poses (guard vs. a kick at its hit) are far apart, and the distance is symmetric.
  const FighterEntry& kick = db.entries[10];
  const std::array<vec3, kPoseKeyPoints> c = entry_pose(kick, kick.hit_frame - kick.start_frame);
  const float ac = pose_points_distance_sq(a, c, nullptr);
  EXPECT_GT(ac, 0.05f);
  EXPECT_NEAR(ac, pose_points_distance_sq(c, a, nullptr), 1e-4f);
}

TEST(PoseClusters, AreDeterministicAndEachPoseSitsInItsNearestCluster) {
  const FighterDatabase db = default_db();
  PoseClusterParams params;
  params.k = 12;
  PoseClusters a, b;
  pose_clusters_compute(db, params, a);
  pose_clusters_compute(db, params, b);
  ASSERT_EQ(a.k, 12);
  ASSERT_EQ(a.num_poses, fighter_database_num_poses(db));
  EXPECT_EQ(a.assignment, b.assignment);
  EXPECT_EQ(a.centroid_pts, b.centroid_pts);
  std::vector<int> members(static_cast<std::size_t>(a.k), 0);
  int pose = 0;
  for (const FighterEntry& e : db.entries)
    for (int f = 0; f < e.num_frames(); ++f, ++pose) {
      PoseCloud cloud;
      pose_cloud_from_points(entry_pose(e, f), cloud);
      const int mine = a.assignment[static_cast<std::size_t>(pose)];
      ++members[static_cast<std::size_t>(mine)];
      float c = 0.0f, s = 0.0f;
      const auto dist = [&](int j) {
        return pose_cloud_distance_sq(a.centroid_pts.data() + static_cast<std::size_t>(j) * kPoseCloudFloats,
                                      a.centroid_sum_sq_xz[static_cast<std::size_t>(j)], cloud.pts.data(), cloud.sum_sq_xz, c, s);
      };
      for (int j = 0; j < a.k; ++j) EXPECT_LE(dist(mine), dist(j) + 1e-6f);
    }
  for (int m : members) EXPECT_GT(m, 0);  // no empty cluster
}

TEST(PoseClusters, GroupTheGuardStartsTogether) {
  // Every default strike starts in the same guard stance: their first poses share a cluster.
  const FighterDatabase db = default_db();
  PoseClusterParams params;
  params.k = 12;
  PoseClusters c;
  pose_clusters_compute(db, params, c);
  int pose = 0;
  std::set<int> first_clusters;
  for (const FighterEntry& e : db.entries) {
    first_clusters.insert(c.assignment[static_cast<std::size_t>(pose)]);
    pose += e.num_frames();
  }
  EXPECT_EQ(first_clusters.size(), 1u);
}

TEST(PoseClusters, CacheHitMissAndCorruption) {
  const std::filesystem::path dir = test::scratch_dir();
  const FighterDatabase db = default_db();
  PoseClusterParams params;
  params.k = 10;
  PoseClusters built, cached;
  ClusterCacheStatus status{};
  std::string warning;
  pose_clusters_load_or_compute(db, params, dir, built, status, warning);
  EXPECT_EQ(status, ClusterCacheStatus::kMissBuilt);
  EXPECT_TRUE(warning.empty()) << warning;
  const std::filesystem::path file = pose_clusters_cache_path(dir, built.hash);
  ASSERT_TRUE(std::filesystem::exists(file));

  pose_clusters_load_or_compute(db, params, dir, cached, status, warning);
  EXPECT_EQ(status, ClusterCacheStatus::kHit);
  EXPECT_EQ(cached.assignment, built.assignment);
  EXPECT_EQ(cached.centroid_pts, built.centroid_pts);

  // Another k is another cache file.
  PoseClusterParams other = params;
  other.k = 11;
  pose_clusters_load_or_compute(db, other, dir, cached, status, warning);
  EXPECT_EQ(status, ClusterCacheStatus::kMissBuilt);
  EXPECT_NE(pose_clusters_cache_path(dir, cached.hash), file);

  // A changed clip (one key point moved) is another cache file too.
  FighterDatabase changed = db;
  changed.entries[4].key_points[7].y += 0.01f;
  EXPECT_NE(pose_clusters_hash(changed, params), built.hash);

  // One flipped byte in the payload: caught by the checksum, rebuilt, rewritten.
  {
    std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(40);
    char byte = 0;
    f.read(&byte, 1);
    f.seekp(40);
    byte = static_cast<char>(byte ^ 0x5a);
    f.write(&byte, 1);
  }
  pose_clusters_load_or_compute(db, params, dir, cached, status, warning);
  EXPECT_EQ(status, ClusterCacheStatus::kCorruptRebuilt);
  EXPECT_EQ(cached.assignment, built.assignment);
  pose_clusters_load_or_compute(db, params, dir, cached, status, warning);
  EXPECT_EQ(status, ClusterCacheStatus::kHit);

  // A truncated file, and one of another program: rebuilt as well.
  std::filesystem::resize_file(file, 30);
  pose_clusters_load_or_compute(db, params, dir, cached, status, warning);
  EXPECT_EQ(status, ClusterCacheStatus::kCorruptRebuilt);
  std::ofstream(file, std::ios::binary | std::ios::trunc) << "not a cluster cache at all, but long enough to read a header";
  pose_clusters_load_or_compute(db, params, dir, cached, status, warning);
  EXPECT_EQ(status, ClusterCacheStatus::kCorruptRebuilt);
  EXPECT_EQ(cached.assignment, built.assignment);
}

TEST(PoseClusters, AutomaticKGrowsWithTheDatabase) {
  const FighterDatabase db = default_db();
  PoseClusters small, large;
  pose_clusters_compute(db, PoseClusterParams{}, small);
  pose_clusters_compute(fighter_database_synthetic(db, 400, 3), PoseClusterParams{}, large);
  EXPECT_GT(small.k, 5);
  EXPECT_GT(large.k, small.k);
  EXPECT_LE(large.k, 256);
}

}  // namespace
}  // namespace foresight

#pragma once
// k-means over every pose of every strike entry (paper 3.2.2) under the aligned point-cloud
// distance (pose_cloud.hpp), precomputed offline and cached on disk.
//
// Algorithm: k-means++ seeding from a fixed-seed generator, then Lloyd iterations where a centroid
// is the mean of its members each first aligned onto it (rotation about Y + ground translation),
// so the centroid is a pose too. Large databases iterate on an evenly strided sample of poses
// (max_sample_poses) and then assign every pose once: the 10,000-clip benchmark database has a
// quarter of a million poses, and the sample's centroids are as good for picking a cluster.
//
// Cache: `<cache_dir>/fighter-clusters-<hash>.bin`, hash = XXH3 of the key points of every entry
// (in order) and the parameters; a changed clip, window or k gives another file. A file whose
// magic, version, hash, sizes, payload checksum or values do not check out is rebuilt and
// rewritten, never trusted.
#include "fighter/fighter_database.hpp"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace foresight {

struct PoseClusterParams {
  int k = 0;                     ///< Clusters; 0: sqrt(poses / 16), clamped to [1, 256].
  int max_iterations = 20;       ///< Lloyd iterations (stops earlier when nothing moves).
  std::uint64_t seed = 1;        ///< k-means++ seeding.
  int max_sample_poses = 8192;   ///< Iterate on at most this many poses (then assign all).
};

/// The clustering result: which cluster each pose belongs to, and the centroids.
struct PoseClusters {
  int k = 0;
  int num_poses = 0;
  std::vector<float> centroid_pts;       ///< [c * kPoseCloudFloats ...], hot-path layout (centred).
  std::vector<float> centroid_sum_sq_xz; ///< Per centroid.
  std::vector<std::int32_t> assignment;  ///< Per pose, entries in order, frames in order.
  std::uint64_t hash = 0;                ///< Content hash of the inputs (names the cache file).
};

enum class ClusterCacheStatus : std::uint8_t {
  kNotUsed,         ///< No cache folder given: computed.
  kHit,             ///< Read from the cache.
  kMissBuilt,       ///< No cache file: computed and written.
  kCorruptRebuilt,  ///< A cache file was there but failed a check: computed and rewritten.
};
std::string_view cluster_cache_status_name(ClusterCacheStatus status);

/// Number of poses of a database (sum of the entries' frame counts).
int fighter_database_num_poses(const FighterDatabase& db);

/// The content hash of the clustering inputs.
std::uint64_t pose_clusters_hash(const FighterDatabase& db, const PoseClusterParams& params);

/// Clusters every pose. Deterministic for a given database and parameters.
void pose_clusters_compute(const FighterDatabase& db, const PoseClusterParams& params, PoseClusters& out);

/// Reads `<cache_dir>/fighter-clusters-<hash>.bin` when valid, else computes and writes it (a
/// cache that cannot be written is reported in `warning`, not an error). Empty cache_dir: no cache.
void pose_clusters_load_or_compute(const FighterDatabase& db, const PoseClusterParams& params,
                                   const std::filesystem::path& cache_dir, PoseClusters& out,
                                   ClusterCacheStatus& status, std::string& warning);

/// The cache file for these inputs.
std::filesystem::path pose_clusters_cache_path(const std::filesystem::path& cache_dir, std::uint64_t hash);

}  // namespace foresight

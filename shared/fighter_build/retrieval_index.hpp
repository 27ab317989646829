#pragma once
// Build time: the retrieval index (fighter/retrieval.hpp's FighterRetrievalIndex, which the
// runtime's FighterRetriever reads) from a fighter database and its pose clusters.
#include "fighter/fighter_database.hpp"
#include "fighter/retrieval.hpp"
#include "fighter_build/pose_clusters.hpp"

#include <filesystem>
#include <string>

namespace foresight {

struct RetrievalIndexParams {
  int min_lead_frames = 3;    ///< A start pose lies at least this many frames before the hit.
  int hit_window_frames = 3;  ///< d_target over [hit - w, hit + w].
};

void fighter_retrieval_index_build(const FighterDatabase& db, const PoseClusters& clusters,
                                   const RetrievalIndexParams& params, FighterRetrievalIndex& out);

/// Clusters (through the cache in `cache_dir`; empty: no cache) and builds the index: everything
/// the offline side does once a database is loaded. `status` and `warning` as
/// pose_clusters_load_or_compute.
void fighter_retrieval_prepare(const FighterDatabase& db, const PoseClusterParams& cluster_params,
                               const RetrievalIndexParams& index_params, const std::filesystem::path& cache_dir,
                               FighterRetrievalIndex& out, ClusterCacheStatus* status, std::string* warning);

}  // namespace foresight

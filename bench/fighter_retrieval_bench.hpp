#pragma once
// The retrieval half of `foresight-bench fighter`: microseconds per retrieval (paper 3.3) over
// random start poses and targets, on a paper-sized database (75 entries: the default strikes, the
// mocap strikes when ../shared/mocap is there, padded with synthetic variants) and on a synthetic
// 10,000-entry one. Queries are generated before timing; each query is timed on its own with
// steady_clock (about 20-30 ns of clock overhead included in every figure).
#include "bench_json.hpp"
#include "fighter_build/pose_clusters.hpp"

#include <cstdint>
#include <filesystem>
#include <string>

namespace foresight::bench {

struct FighterRetrievalBenchConfig {
  std::filesystem::path mocap_fighting_dir;  ///< Empty or absent: default strikes only.
  std::filesystem::path sidecar;             ///< Strike sidecar for that folder (empty: the folder's own / detection).
  std::filesystem::path cache_dir;           ///< Cluster cache; empty: clusters computed every run.
  int small_entries = 75;                    ///< The paper's database size.
  int large_entries = 10000;
  int queries = 20000;                       ///< Timed queries per database.
  int capped_clusters = 16;                  ///< RetrievalParams::max_clusters of the capped run.
  std::uint64_t seed = 1;
};

/// One database's figures.
struct RetrievalTiming {
  int entries = 0;
  int poses = 0;            ///< Every pose (clustered).
  int start_poses = 0;      ///< Candidate start poses in the index.
  int clusters = 0;
  double prepare_s = 0.0;   ///< Clustering (or cache read) + index build.
  ClusterCacheStatus cache = ClusterCacheStatus::kNotUsed;
  int queries = 0;
  double us_p50 = 0.0, us_p99 = 0.0, us_max = 0.0, us_mean = 0.0;
  double in_cluster_share = 0.0;  ///< Answered from the nearest cluster (no widening).
  double widened_share = 0.0;     ///< From the next nearest clusters.
  double all_share = 0.0;         ///< From a search of every cluster.
  double no_box_share = 0.0;      ///< No box held the target (best start of the nearest clusters).
  double mean_scored = 0.0;       ///< Candidates costed per query.
};

struct FighterRetrievalBenchResult {
  int default_entries = 0;  ///< Default library strikes in the small database.
  int mocap_entries = 0;    ///< Captured strikes in it (0 without ../shared/mocap).
  int padded_entries = 0;   ///< Synthetic variants added to reach small_entries.
  RetrievalTiming small;
  RetrievalTiming large;
  RetrievalTiming large_capped;  ///< The large database with max_clusters = capped_clusters.
  int capped_clusters = 0;
  std::string error;        ///< Non-empty: the database could not be built (nothing timed).
};

FighterRetrievalBenchResult run_fighter_retrieval_bench(const FighterRetrievalBenchConfig& config);

/// {"retrieval_default_entries":..,"retrieval_us_p50":..,"retrieval_10k_us_p50":..,...}: one JSON
/// object, the figures rounded. retrieval_us_* are the small database's.
Json to_json(const FighterRetrievalBenchResult& result);

/// Human-readable lines (each ending with a newline).
std::string describe(const FighterRetrievalBenchResult& result);

}  // namespace foresight::bench

#include "fighter_retrieval_bench.hpp"
#include "fighter_build/retrieval_index.hpp"
#include "fighter_build/fighter_database_build.hpp"

#include "fighter/retrieval.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <string>
#include <system_error>
#include <vector>

namespace foresight::bench {
namespace {

using Clock = std::chrono::steady_clock;

double unit(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * (1.0 / 9007199254740992.0); }
float uniform(std::mt19937_64& rng, float lo, float hi) { return lo + static_cast<float>(unit(rng)) * (hi - lo); }

// Random fighters: a start pose taken from a random entry frame in the first half of its approach
// (guard and wind-up poses: where a fighter is when the supervisor orders), a fighter 0.85-1.2
// times the default size, 1 cm of key-point noise, a target in front of it anywhere from knee to
// above head height, and an order of punch, kick or either.
std::vector<RetrievalQuery> make_queries(const FighterDatabase& db, int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<RetrievalQuery> out(static_cast<std::size_t>(count));
  for (RetrievalQuery& q : out) {
    const FighterEntry& e = db.entries[static_cast<std::size_t>(rng() % db.entries.size())];
    const int frame = static_cast<int>(rng() % static_cast<std::uint64_t>(std::max(1, (e.hit_frame - e.start_frame) / 2)));
    q.body_size_m = 1.45f * uniform(rng, 0.85f, 1.2f);
    for (int i = 0; i < kPoseKeyPoints; ++i) {
      const vec3 noise(uniform(rng, -0.01f, 0.01f), uniform(rng, -0.01f, 0.01f), uniform(rng, -0.01f, 0.01f));
      q.pose_key_points_m[static_cast<std::size_t>(i)] =
          (e.key_points[static_cast<std::size_t>(frame * kPoseKeyPoints + i)] + noise) * q.body_size_m;
    }
    const float s = q.body_size_m / 1.45f;
    q.target_m = vec3(uniform(rng, -0.4f, 0.4f), uniform(rng, 0.5f, 1.8f), uniform(rng, 0.3f, 1.1f)) * s;
    const std::uint64_t order = rng() % 3;
    if (order == 1) q.kind = StrikeKind::kPunch;
    if (order == 2) q.kind = StrikeKind::kKick;
  }
  return out;
}

RetrievalTiming time_database(const FighterDatabase& db, const FighterRetrievalBenchConfig& config,
                              std::uint64_t seed, const RetrievalParams& params) {
  RetrievalTiming t;
  t.entries = static_cast<int>(db.entries.size());
  t.poses = fighter_database_num_poses(db);
  FighterRetrievalIndex index;
  const Clock::time_point p0 = Clock::now();
  fighter_retrieval_prepare(db, PoseClusterParams{}, RetrievalIndexParams{}, config.cache_dir, index, &t.cache, nullptr);
  t.prepare_s = std::chrono::duration<double>(Clock::now() - p0).count();
  t.clusters = index.k;
  t.start_poses = index.cluster_begin.empty() ? 0 : index.cluster_begin.back();

  const std::vector<RetrievalQuery> queries = make_queries(db, config.queries, seed);
  FighterRetriever retriever(index);
  RetrievalResult r;
  for (int i = 0; i < std::min(500, config.queries); ++i) retriever.retrieve(queries[static_cast<std::size_t>(i)], params, r);

  std::vector<double> us(queries.size());
  long scopes[4] = {0, 0, 0, 0};
  double scored = 0.0;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    const Clock::time_point a = Clock::now();
    retriever.retrieve(queries[i], params, r);
    const Clock::time_point b = Clock::now();
    us[i] = std::chrono::duration<double, std::micro>(b - a).count();
    ++scopes[static_cast<int>(r.scope)];
    scored += r.candidates_scored;
  }
  t.queries = static_cast<int>(queries.size());
  if (us.empty()) return t;
  double sum = 0.0;
  for (double v : us) sum += v;
  t.us_mean = sum / static_cast<double>(us.size());
  std::sort(us.begin(), us.end());
  t.us_p50 = us[us.size() / 2];
  t.us_p99 = us[std::min(us.size() - 1, us.size() * 99 / 100)];
  t.us_max = us.back();
  const double n = static_cast<double>(us.size());
  t.in_cluster_share = static_cast<double>(scopes[0]) / n;
  t.widened_share = static_cast<double>(scopes[1]) / n;
  t.all_share = static_cast<double>(scopes[2]) / n;
  t.no_box_share = static_cast<double>(scopes[3]) / n;
  t.mean_scored = scored / static_cast<double>(us.size());
  return t;
}

// One database's figures into `j`, every key starting with `prefix`.
void add_timing(Json& j, const std::string& prefix, const RetrievalTiming& t) {
  j[prefix + "us_p50"] = rounded(t.us_p50, 3);
  j[prefix + "us_p99"] = rounded(t.us_p99, 3);
  j[prefix + "us_max"] = rounded(t.us_max, 3);
  j[prefix + "entries"] = t.entries;
  j[prefix + "poses"] = t.poses;
  j[prefix + "clusters"] = t.clusters;
  j[prefix + "prepare_s"] = rounded(t.prepare_s, 3);
  j[prefix + "in_cluster_share"] = rounded(t.in_cluster_share, 3);
}

std::string timing_line(const char* name, const RetrievalTiming& t) {
  char buf[768];
  std::snprintf(buf, sizeof buf,
                "%s: %d entries, %d poses (%d start poses) in %d clusters, prepared in %.3f s (cache %s)\n"
                "  retrieval: p50 %.2f us, p99 %.2f us, max %.2f us, mean %.2f us over %d queries; "
                "%.1f candidates costed per query\n"
                "  answered from: nearest cluster %.1f%%, widened %.1f%%, all clusters %.1f%%, no box holds the "
                "target %.1f%%\n",
                name, t.entries, t.poses, t.start_poses, t.clusters, t.prepare_s,
                std::string(cluster_cache_status_name(t.cache)).c_str(), t.us_p50, t.us_p99, t.us_max, t.us_mean,
                t.queries, t.mean_scored, 100.0 * t.in_cluster_share, 100.0 * t.widened_share, 100.0 * t.all_share,
                100.0 * t.no_box_share);
  return buf;
}

}  // namespace

FighterRetrievalBenchResult run_fighter_retrieval_bench(const FighterRetrievalBenchConfig& config) {
  FighterRetrievalBenchResult result;
  FighterDatabase real;
  if (!fighter_database_add_default_library(real, result.error)) return result;
  result.default_entries = static_cast<int>(real.entries.size());
  std::error_code ec;
  if (!config.mocap_fighting_dir.empty() && std::filesystem::is_directory(config.mocap_fighting_dir, ec)) {
    if (!fighter_database_add_folder(real, config.mocap_fighting_dir, config.sidecar, StrikeSplitParams{}, nullptr,
                                     result.error))
      return result;
    result.mocap_entries = static_cast<int>(real.entries.size()) - result.default_entries;
  }
  // Pad to the paper's size with variants of the real strikes.
  FighterDatabase small = real;
  const int missing = config.small_entries - static_cast<int>(real.entries.size());
  if (missing > 0) {
    FighterDatabase pad = fighter_database_synthetic(real, missing, config.seed);
    for (FighterEntry& e : pad.entries) small.entries.push_back(std::move(e));
    result.padded_entries = missing;
  }
  result.small = time_database(small, config, config.seed + 1, RetrievalParams{});
  const FighterDatabase large = fighter_database_synthetic(real, config.large_entries, config.seed + 2);
  result.large = time_database(large, config, config.seed + 3, RetrievalParams{});
  RetrievalParams capped;
  capped.max_clusters = config.capped_clusters;
  result.capped_clusters = config.capped_clusters;
  result.large_capped = time_database(large, config, config.seed + 3, capped);
  return result;
}

Json to_json(const FighterRetrievalBenchResult& r) {
  Json j = {{"retrieval_default_entries", r.default_entries},
            {"retrieval_mocap_entries", r.mocap_entries},
            {"retrieval_padded_entries", r.padded_entries}};
  add_timing(j, "retrieval_", r.small);
  add_timing(j, "retrieval_10k_", r.large);
  add_timing(j, "retrieval_10k_capped_", r.large_capped);
  j["retrieval_10k_cap_max_clusters"] = r.capped_clusters;
  return j;
}

std::string describe(const FighterRetrievalBenchResult& r) {
  if (!r.error.empty()) return "fighter retrieval: " + r.error + "\n";
  char head[256];
  std::snprintf(head, sizeof head, "fighter retrieval: small database = %d default + %d mocap + %d synthetic entries\n",
                r.default_entries, r.mocap_entries, r.padded_entries);
  return std::string(head) + timing_line("small", r.small) + timing_line("large", r.large) +
         timing_line(("large, searching at most " + std::to_string(r.capped_clusters) + " clusters").c_str(),
                     r.large_capped);
}

}  // namespace foresight::bench

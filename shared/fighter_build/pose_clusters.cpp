#include "fighter_build/pose_clusters.hpp"

#include "io/text_file.hpp"

#include <xxhash.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>
#include <system_error>

namespace foresight {
namespace {

constexpr char kMagic[4] = {'F', 'S', 'C', 'L'};
constexpr std::uint32_t kCacheVersion = 1;
constexpr std::uint32_t kHashVersion = 3;  // Bump when the key points or the algorithm change.

// Every pose of the database in the hot-path layout.
struct PoseTable {
  int n = 0;
  std::vector<float> pts;
  std::vector<float> ss;
  const float* row(int i) const { return pts.data() + static_cast<std::size_t>(i) * kPoseCloudFloats; }
};

void build_table(const FighterDatabase& db, PoseTable& t) {
  t.n = fighter_database_num_poses(db);
  t.pts.resize(static_cast<std::size_t>(t.n) * kPoseCloudFloats);
  t.ss.resize(static_cast<std::size_t>(t.n));
  int i = 0;
  for (const FighterEntry& e : db.entries)
    for (int f = 0; f < e.num_frames(); ++f, ++i) {
      vec2 centroid;
      pose_cloud_pack(std::span<const vec3, kPoseKeyPoints>(e.key_points.data() + static_cast<std::size_t>(f) * kPoseKeyPoints,
                                                            kPoseKeyPoints),
                      t.pts.data() + static_cast<std::size_t>(i) * kPoseCloudFloats, t.ss[static_cast<std::size_t>(i)],
                      centroid);
    }
}

int effective_k(const PoseClusterParams& p, int n) {
  if (n <= 0) return 0;
  // Automatic k: about 4 sqrt(n) poses per cluster. Fewer, larger clusters than sqrt(n) because
  // the retrieval drops most of a cluster with the box test: a cluster of a few hundred start
  // poses too often has no survivor and sends the search wider (measured: docs/FIGHTER_DATABASE.md).
  const int k = p.k > 0 ? p.k : std::clamp(static_cast<int>(std::lround(std::sqrt(n / 16.0))), 1, 256);
  return std::min(k, n);
}

double unit(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * (1.0 / 9007199254740992.0); }

// Nearest centroid of one pose.
int nearest(const PoseClusters& c, const float* p, float p_ss, float& best_d) {
  int best = 0;
  best_d = std::numeric_limits<float>::max();
  float cc = 0.0f, s = 0.0f;
  for (int j = 0; j < c.k; ++j) {
    const float d = pose_cloud_distance_sq(c.centroid_pts.data() + static_cast<std::size_t>(j) * kPoseCloudFloats,
                                           c.centroid_sum_sq_xz[static_cast<std::size_t>(j)], p, p_ss, cc, s);
    if (d < best_d) {
      best_d = d;
      best = j;
    }
  }
  return best;
}

void set_centroid(PoseClusters& c, int j, const float* pts) {
  float* dst = c.centroid_pts.data() + static_cast<std::size_t>(j) * kPoseCloudFloats;
  // Recentre xz (averaging aligned clouds keeps them centred up to rounding).
  float mx = 0.0f, mz = 0.0f;
  for (int i = 0; i < kPoseKeyPoints; ++i) {
    mx += pts[i];
    mz += pts[2 * kPoseKeyPoints + i];
  }
  mx /= kPoseKeyPoints;
  mz /= kPoseKeyPoints;
  float ss = 0.0f;
  for (int i = 0; i < kPoseKeyPoints; ++i) {
    dst[i] = pts[i] - mx;
    dst[kPoseKeyPoints + i] = pts[kPoseKeyPoints + i];
    dst[2 * kPoseKeyPoints + i] = pts[2 * kPoseKeyPoints + i] - mz;
    ss += dst[i] * dst[i] + dst[2 * kPoseKeyPoints + i] * dst[2 * kPoseKeyPoints + i];
  }
  c.centroid_sum_sq_xz[static_cast<std::size_t>(j)] = ss;
}

void seed_kmeanspp(const PoseTable& t, const std::vector<int>& sample, std::uint64_t seed, PoseClusters& c) {
  std::mt19937_64 rng(seed);
  const std::size_t s = sample.size();
  std::vector<double> d2(s, std::numeric_limits<double>::max());
  int chosen = sample[static_cast<std::size_t>(unit(rng) * static_cast<double>(s)) % s];
  float cc = 0.0f, ssn = 0.0f;
  for (int j = 0; j < c.k; ++j) {
    set_centroid(c, j, t.row(chosen));
    double total = 0.0;
    for (std::size_t i = 0; i < s; ++i) {
      const int p = sample[i];
      const double d = pose_cloud_distance_sq(c.centroid_pts.data() + static_cast<std::size_t>(j) * kPoseCloudFloats,
                                              c.centroid_sum_sq_xz[static_cast<std::size_t>(j)], t.row(p),
                                              t.ss[static_cast<std::size_t>(p)], cc, ssn);
      d2[i] = std::min(d2[i], d);
      total += d2[i];
    }
    if (j + 1 == c.k) break;
    // Next centre drawn with probability proportional to D^2; all poses equal: any will do.
    double pick = unit(rng) * total;
    std::size_t next = s - 1;
    for (std::size_t i = 0; i < s; ++i) {
      pick -= d2[i];
      if (pick < 0.0) {
        next = i;
        break;
      }
    }
    chosen = sample[next];
  }
}

// One Lloyd step on `sample`; returns how many assignments changed.
int lloyd_step(const PoseTable& t, const std::vector<int>& sample, std::vector<int>& assign, PoseClusters& c,
               std::vector<float>& sums, std::vector<int>& counts) {
  int changed = 0;
  std::fill(sums.begin(), sums.end(), 0.0f);
  std::fill(counts.begin(), counts.end(), 0);
  float worst_d = -1.0f;
  int worst = sample.front();
  for (std::size_t i = 0; i < sample.size(); ++i) {
    const int p = sample[i];
    float d = 0.0f;
    const int j = nearest(c, t.row(p), t.ss[static_cast<std::size_t>(p)], d);
    if (assign[i] != j) ++changed;
    assign[i] = j;
    if (d > worst_d) {
      worst_d = d;
      worst = p;
    }
    // The member aligned onto its centroid: both centred, so only the rotation remains.
    float cc = 0.0f, s = 0.0f;
    pose_cloud_distance_sq(c.centroid_pts.data() + static_cast<std::size_t>(j) * kPoseCloudFloats,
                           c.centroid_sum_sq_xz[static_cast<std::size_t>(j)], t.row(p), t.ss[static_cast<std::size_t>(p)],
                           cc, s);
    const float r = std::sqrt(cc * cc + s * s);
    const float ch = r > 1e-12f ? cc / r : 1.0f, sh = r > 1e-12f ? s / r : 0.0f;
    const float* b = t.row(p);
    float* acc = sums.data() + static_cast<std::size_t>(j) * kPoseCloudFloats;
    for (int k = 0; k < kPoseKeyPoints; ++k) {
      const float x = b[k], z = b[2 * kPoseKeyPoints + k];
      acc[k] += ch * x + sh * z;
      acc[kPoseKeyPoints + k] += b[kPoseKeyPoints + k];
      acc[2 * kPoseKeyPoints + k] += -sh * x + ch * z;
    }
    ++counts[static_cast<std::size_t>(j)];
  }
  std::vector<float> mean(kPoseCloudFloats);
  for (int j = 0; j < c.k; ++j) {
    const int n = counts[static_cast<std::size_t>(j)];
    if (n == 0) {
      // An empty cluster restarts on the worst-served pose, so k stays meaningful.
      set_centroid(c, j, t.row(worst));
      ++changed;
      continue;
    }
    for (int k = 0; k < kPoseCloudFloats; ++k)
      mean[static_cast<std::size_t>(k)] = sums[static_cast<std::size_t>(j) * kPoseCloudFloats + static_cast<std::size_t>(k)] / static_cast<float>(n);
    set_centroid(c, j, mean.data());
  }
  return changed;
}

template <typename T>
void put(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof(T));
}
template <typename T>
bool get(const std::string& in, std::size_t& at, T& v) {
  if (at + sizeof(T) > in.size()) return false;
  std::memcpy(&v, in.data() + at, sizeof(T));
  at += sizeof(T);
  return true;
}

std::string serialize(const PoseClusters& c) {
  std::string out;
  out.append(kMagic, 4);
  put(out, kCacheVersion);
  put(out, c.hash);
  put(out, static_cast<std::uint32_t>(c.k));
  put(out, static_cast<std::uint32_t>(c.num_poses));
  out.append(reinterpret_cast<const char*>(c.centroid_pts.data()), c.centroid_pts.size() * sizeof(float));
  out.append(reinterpret_cast<const char*>(c.centroid_sum_sq_xz.data()), c.centroid_sum_sq_xz.size() * sizeof(float));
  out.append(reinterpret_cast<const char*>(c.assignment.data()), c.assignment.size() * sizeof(std::int32_t));
  put(out, static_cast<std::uint64_t>(XXH3_64bits(out.data(), out.size())));
  return out;
}

// Every check a cache file must pass; false means "rebuild".
bool deserialize(const std::string& in, std::uint64_t hash, int num_poses, PoseClusters& c) {
  std::size_t at = 0;
  if (in.size() < 4 + 4 + 8 + 4 + 4 + 8 || std::memcmp(in.data(), kMagic, 4) != 0) return false;
  at = 4;
  std::uint32_t version = 0, k = 0, n = 0;
  std::uint64_t file_hash = 0;
  if (!get(in, at, version) || version != kCacheVersion || !get(in, at, file_hash) || file_hash != hash ||
      !get(in, at, k) || !get(in, at, n) || static_cast<int>(n) != num_poses || k == 0 || k > static_cast<std::uint32_t>(num_poses))
    return false;
  const std::size_t payload = static_cast<std::size_t>(k) * (kPoseCloudFloats + 1) * sizeof(float) +
                              static_cast<std::size_t>(n) * sizeof(std::int32_t);
  if (in.size() != at + payload + sizeof(std::uint64_t)) return false;
  std::uint64_t checksum = 0;
  std::size_t tail = at + payload;
  get(in, tail, checksum);
  if (checksum != XXH3_64bits(in.data(), at + payload)) return false;
  c.k = static_cast<int>(k);
  c.num_poses = static_cast<int>(n);
  c.hash = hash;
  c.centroid_pts.resize(static_cast<std::size_t>(k) * kPoseCloudFloats);
  c.centroid_sum_sq_xz.resize(k);
  c.assignment.resize(n);
  std::memcpy(c.centroid_pts.data(), in.data() + at, c.centroid_pts.size() * sizeof(float));
  at += c.centroid_pts.size() * sizeof(float);
  std::memcpy(c.centroid_sum_sq_xz.data(), in.data() + at, c.centroid_sum_sq_xz.size() * sizeof(float));
  at += c.centroid_sum_sq_xz.size() * sizeof(float);
  std::memcpy(c.assignment.data(), in.data() + at, c.assignment.size() * sizeof(std::int32_t));
  for (float v : c.centroid_pts)
    if (!std::isfinite(v)) return false;
  for (float v : c.centroid_sum_sq_xz)
    if (!std::isfinite(v) || v < 0.0f) return false;
  for (std::int32_t a : c.assignment)
    if (a < 0 || a >= c.k) return false;
  return true;
}

bool read_file(const std::filesystem::path& path, std::string& out) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return false;
  f.seekg(0, std::ios::end);
  const std::streamoff size = f.tellg();
  if (size < 0 || size > (std::streamoff{1} << 31)) return false;
  out.resize(static_cast<std::size_t>(size));
  f.seekg(0);
  f.read(out.data(), size);
  return static_cast<bool>(f);
}

bool write_file(const std::filesystem::path& path, const std::string& bytes, std::string& warning) {
  std::error_code ec;
  std::filesystem::create_directories(path.parent_path(), ec);
  if (file_write_atomic(path, bytes, warning)) return true;
  warning = "cannot write the cluster cache: " + warning;
  return false;
}

}  // namespace

std::string_view cluster_cache_status_name(ClusterCacheStatus status) {
  switch (status) {
    case ClusterCacheStatus::kNotUsed: return "not used";
    case ClusterCacheStatus::kHit: return "hit";
    case ClusterCacheStatus::kMissBuilt: return "miss (built)";
    case ClusterCacheStatus::kCorruptRebuilt: return "corrupt (rebuilt)";
  }
  return "?";
}

int fighter_database_num_poses(const FighterDatabase& db) {
  int n = 0;
  for (const FighterEntry& e : db.entries) n += e.num_frames();
  return n;
}

std::uint64_t pose_clusters_hash(const FighterDatabase& db, const PoseClusterParams& params) {
  XXH3_state_t* state = XXH3_createState();
  XXH3_64bits_reset(state);
  const auto add = [&](const auto& v) { XXH3_64bits_update(state, &v, sizeof(v)); };
  add(kHashVersion);
  add(static_cast<std::int32_t>(kPoseKeyPoints));
  add(static_cast<std::int32_t>(params.k));
  add(static_cast<std::int32_t>(params.max_iterations));
  add(params.seed);
  add(static_cast<std::int32_t>(params.max_sample_poses));
  add(static_cast<std::uint64_t>(db.entries.size()));
  for (const FighterEntry& e : db.entries) {
    add(static_cast<std::int32_t>(e.num_frames()));
    XXH3_64bits_update(state, e.key_points.data(), e.key_points.size() * sizeof(vec3));
  }
  const std::uint64_t h = XXH3_64bits_digest(state);
  XXH3_freeState(state);
  return h;
}

void pose_clusters_compute(const FighterDatabase& db, const PoseClusterParams& params, PoseClusters& out) {
  PoseTable t;
  build_table(db, t);
  out = PoseClusters{};
  out.num_poses = t.n;
  out.hash = pose_clusters_hash(db, params);
  out.k = effective_k(params, t.n);
  if (out.k == 0) return;
  out.centroid_pts.assign(static_cast<std::size_t>(out.k) * kPoseCloudFloats, 0.0f);
  out.centroid_sum_sq_xz.assign(static_cast<std::size_t>(out.k), 0.0f);

  // An evenly strided sample (every pose when the database is small).
  const int s = std::min(t.n, std::max(out.k, params.max_sample_poses));
  std::vector<int> sample(static_cast<std::size_t>(s));
  for (int i = 0; i < s; ++i)
    sample[static_cast<std::size_t>(i)] = static_cast<int>(static_cast<std::int64_t>(i) * t.n / s);

  seed_kmeanspp(t, sample, params.seed, out);
  std::vector<int> assign(sample.size(), -1);
  std::vector<float> sums(out.centroid_pts.size());
  std::vector<int> counts(static_cast<std::size_t>(out.k));
  for (int it = 0; it < params.max_iterations; ++it)
    if (lloyd_step(t, sample, assign, out, sums, counts) == 0) break;

  out.assignment.resize(static_cast<std::size_t>(t.n));
  for (int p = 0; p < t.n; ++p) {
    float d = 0.0f;
    out.assignment[static_cast<std::size_t>(p)] = nearest(out, t.row(p), t.ss[static_cast<std::size_t>(p)], d);
  }
}

std::filesystem::path pose_clusters_cache_path(const std::filesystem::path& cache_dir, std::uint64_t hash) {
  char name[64];
  std::snprintf(name, sizeof name, "fighter-clusters-%016llx.bin", static_cast<unsigned long long>(hash));
  return cache_dir / name;
}

void pose_clusters_load_or_compute(const FighterDatabase& db, const PoseClusterParams& params,
                                   const std::filesystem::path& cache_dir, PoseClusters& out,
                                   ClusterCacheStatus& status, std::string& warning) {
  warning.clear();
  if (cache_dir.empty()) {
    pose_clusters_compute(db, params, out);
    status = ClusterCacheStatus::kNotUsed;
    return;
  }
  const std::uint64_t hash = pose_clusters_hash(db, params);
  const std::filesystem::path path = pose_clusters_cache_path(cache_dir, hash);
  std::string bytes;
  std::error_code ec;
  const bool present = std::filesystem::exists(path, ec);
  if (present && read_file(path, bytes) && deserialize(bytes, hash, fighter_database_num_poses(db), out)) {
    status = ClusterCacheStatus::kHit;
    return;
  }
  pose_clusters_compute(db, params, out);
  status = present ? ClusterCacheStatus::kCorruptRebuilt : ClusterCacheStatus::kMissBuilt;
  write_file(path, serialize(out), warning);
}

}  // namespace foresight

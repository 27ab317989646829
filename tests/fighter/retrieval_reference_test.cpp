// Equivalence: the filtered, best-first retrieval (retrieval.cpp) against the plain scan it
// replaced (kept here as the reference, verbatim but for one marked change to the no-box
// fallback's widening: every start pose of the searched clusters box-tested and costed, clusters
// widened in the same steps). Same entry, start frame, scope and cost on random queries over the
// default library and a synthetic database, with default, capped and other weights.
#include "fighter/retrieval.hpp"
#include "fighter_build/retrieval_index.hpp"
#include "fighter_build/fighter_database_build.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>

namespace foresight {
namespace reference {

struct RefIndex {
  int k = 0;
  std::vector<float> centroid_pts;  ///< [c * kPoseCloudFloats ...]
  std::vector<float> centroid_ss;
  std::vector<std::int32_t> cluster_begin;  ///< k + 1 offsets into the pose arrays.
  /// Per cluster and kind ([c * 2 + kind]), bounds over its start poses for skipping a whole
  /// cluster when searching all of them: the height range of the members' hit boxes, and the
  /// least near / greatest far ground distance from a member's centroid to its box (the box
  /// tests below, taken over the cluster; empty clusters hold an empty range).
  std::vector<float> cluster_y_min, cluster_y_max, cluster_near_min, cluster_far_max;
  /// Per cluster: the largest RMS distance (body sizes) from its centroid to one of its start
  /// poses. By the triangle inequality no member is nearer the query than d(query, centroid) minus
  /// this, so once a candidate is in hand a cluster whose bound loses is skipped whole.
  std::vector<float> cluster_radius;
  // Candidate start poses, cluster by cluster.
  std::vector<float> pose_pts;  ///< [p * kPoseCloudFloats ...], centred.
  std::vector<float> pose_ss;
  std::vector<vec2> pose_centroid;
  std::vector<std::int32_t> pose_entry;
  std::vector<std::int32_t> pose_offset;  ///< Frame - entry start.
  std::vector<vec2> pose_centroid_start;  ///< pose_centroid carried into the entry's start frame.
  // Per entry.
  std::vector<std::uint8_t> entry_kind, entry_side;
  std::vector<vec3> entry_box_min, entry_box_max;  ///< Hit path's box, start root frame, body sizes.
  std::vector<std::int32_t> entry_frames_begin;    ///< Into the per-frame arrays.
  std::vector<std::int32_t> entry_hit_offset;      ///< Hit frame - start frame.
  std::vector<std::int32_t> entry_num_frames;
  std::vector<float> entry_body_size_m;
  std::vector<std::int32_t> entry_start_frame;    ///< Take frame of the window's start.
  // Per entry frame: its root placement in the start's root frame (rotation as cos/sin and
  // translation in body sizes), and the hit point (start root frame, body sizes).
  std::vector<float> frame_root_cos, frame_root_sin;
  std::vector<vec2> frame_root_pos;
  std::vector<vec3> frame_hit;
  int hit_window_frames = 3;
};

/// Runs queries against one index. Holds the per-query scratch (sized once here), so retrieve()
/// never allocates; one retriever per thread.
class RefRetriever {
 public:
  explicit RefRetriever(const RefIndex& index);
  /// False (out.entry = -1) for an empty index, body_size_m <= 0, or when no entry has the ordered
  /// kind and side.
  bool retrieve(const RetrievalQuery& query, const RetrievalParams& params, RetrievalResult& out);

 private:
  struct Best;
  void scan(int begin, int end, bool box_test, const RetrievalParams& params, Best& best, RetrievalResult& out) const;
  /// False when no start pose of cluster j can pass the box test (per-cluster bounds).
  bool cluster_may_hold(int j, float margin) const;

  const RefIndex* index_;
  std::vector<float> centroid_d_;
  std::vector<std::int32_t> order_;
  // The prepared query.
  std::array<float, kPoseCloudFloats> q_pts_{};
  float q_ss_ = 0.0f;
  vec2 q_centroid_{0.0f};
  vec3 target_n_{0.0f};
  float rho_sq_ = 0.0f;  ///< Squared ground distance from the target to the pose's centroid.
  int kind_ = -1, side_ = -1;
};

void fighter_retrieval_index_build(const FighterDatabase& db, const PoseClusters& clusters,
                                   const RetrievalIndexParams& params, RefIndex& out) {
  out = RefIndex{};
  assert(clusters.num_poses == fighter_database_num_poses(db));
  out.k = clusters.k;
  out.centroid_pts = clusters.centroid_pts;
  out.centroid_ss = clusters.centroid_sum_sq_xz;
  out.hit_window_frames = params.hit_window_frames;

  // Per entry and per frame.
  const std::size_t num_entries = db.entries.size();
  out.entry_kind.resize(num_entries);
  out.entry_side.resize(num_entries);
  out.entry_box_min.resize(num_entries);
  out.entry_box_max.resize(num_entries);
  out.entry_frames_begin.resize(num_entries);
  out.entry_hit_offset.resize(num_entries);
  out.entry_num_frames.resize(num_entries);
  out.entry_body_size_m.resize(num_entries);
  out.entry_start_frame.resize(num_entries);
  for (std::size_t e = 0; e < num_entries; ++e) {
    const FighterEntry& entry = db.entries[e];
    const float inv = 1.0f / entry.body_size_m;
    const int n = entry.num_frames();
    const int hit = entry.hit_frame - entry.start_frame;
    out.entry_kind[e] = static_cast<std::uint8_t>(entry.kind);
    out.entry_side[e] = static_cast<std::uint8_t>(entry.side);
    out.entry_frames_begin[e] = static_cast<std::int32_t>(out.frame_hit.size());
    out.entry_hit_offset[e] = hit;
    out.entry_num_frames[e] = n;
    out.entry_body_size_m[e] = entry.body_size_m;
    out.entry_start_frame[e] = entry.start_frame;
    for (int i = 0; i < n; ++i) {
      const Placement& r = entry.root_from_start_m[static_cast<std::size_t>(i)];
      out.frame_root_cos.push_back(std::cos(r.heading_rad));
      out.frame_root_sin.push_back(std::sin(r.heading_rad));
      out.frame_root_pos.push_back(r.pos_m * inv);
      out.frame_hit.push_back(entry.hit_path_m[static_cast<std::size_t>(i)] * inv);
    }
    // The paper's box: the whole hit trajectory's (a coarse filter; the window decides the cost).
    const vec3 bmin = entry.hit_box_min_m * inv, bmax = entry.hit_box_max_m * inv;
    out.entry_box_min[e] = bmin;
    out.entry_box_max[e] = bmax;
  }

  // Candidate start poses grouped by cluster (a counting sort keeps each cluster contiguous and
  // the order inside it deterministic).
  struct Candidate {
    std::int32_t pose, entry, offset;
  };
  std::vector<Candidate> candidates;
  std::vector<std::int32_t> counts(static_cast<std::size_t>(out.k) + 1, 0);
  int pose = 0;
  for (std::size_t e = 0; e < num_entries; ++e) {
    const FighterEntry& entry = db.entries[e];
    const int last_start = std::max(0, out.entry_hit_offset[e] - params.min_lead_frames);
    for (int i = 0; i < entry.num_frames(); ++i, ++pose) {
      if (i > last_start) continue;
      candidates.push_back({pose, static_cast<std::int32_t>(e), i});
      ++counts[static_cast<std::size_t>(clusters.assignment[static_cast<std::size_t>(pose)]) + 1];
    }
  }
  std::partial_sum(counts.begin(), counts.end(), counts.begin());
  out.cluster_begin = counts;
  const std::size_t m = candidates.size();
  out.pose_pts.resize(m * kPoseCloudFloats);
  out.pose_ss.resize(m);
  out.pose_centroid.resize(m);
  out.pose_entry.resize(m);
  out.pose_offset.resize(m);
  out.pose_centroid_start.resize(m);
  std::vector<std::int32_t> fill(counts.begin(), counts.end() - 1);
  for (const Candidate& c : candidates) {
    const int cluster = clusters.assignment[static_cast<std::size_t>(c.pose)];
    const std::size_t slot = static_cast<std::size_t>(fill[static_cast<std::size_t>(cluster)]++);
    const FighterEntry& entry = db.entries[static_cast<std::size_t>(c.entry)];
    pose_cloud_pack(std::span<const vec3, kPoseKeyPoints>(
                        entry.key_points.data() + static_cast<std::size_t>(c.offset) * kPoseKeyPoints, kPoseKeyPoints),
                    out.pose_pts.data() + slot * kPoseCloudFloats, out.pose_ss[slot], out.pose_centroid[slot]);
    out.pose_entry[slot] = c.entry;
    out.pose_offset[slot] = c.offset;
    // The pose's ground centroid carried into the entry's start frame (for the ring test).
    const std::size_t f = static_cast<std::size_t>(out.entry_frames_begin[static_cast<std::size_t>(c.entry)] + c.offset);
    const vec2 b = out.pose_centroid[slot];
    const float rc = out.frame_root_cos[f], rs = out.frame_root_sin[f];
    out.pose_centroid_start[slot] = vec2(rc * b.x + rs * b.y, -rs * b.x + rc * b.y) + out.frame_root_pos[f];
  }

  out.cluster_radius.assign(static_cast<std::size_t>(out.k), 0.0f);
  for (int j = 0; j < out.k; ++j)
    for (int p = out.cluster_begin[static_cast<std::size_t>(j)]; p < out.cluster_begin[static_cast<std::size_t>(j) + 1]; ++p) {
      float c = 0.0f, s = 0.0f;
      const float d2 = pose_cloud_distance_sq(out.centroid_pts.data() + static_cast<std::size_t>(j) * kPoseCloudFloats,
                                              out.centroid_ss[static_cast<std::size_t>(j)],
                                              out.pose_pts.data() + static_cast<std::size_t>(p) * kPoseCloudFloats,
                                              out.pose_ss[static_cast<std::size_t>(p)], c, s);
      // A little slack for float rounding in the bound.
      out.cluster_radius[static_cast<std::size_t>(j)] =
          std::max(out.cluster_radius[static_cast<std::size_t>(j)], std::sqrt(d2 / kPoseKeyPoints) * 1.001f + 1e-5f);
    }

  // Per-cluster bounds of the box tests, per kind.
  const std::size_t slots = static_cast<std::size_t>(out.k) * 2;
  out.cluster_y_min.assign(slots, std::numeric_limits<float>::max());
  out.cluster_y_max.assign(slots, std::numeric_limits<float>::lowest());
  out.cluster_near_min.assign(slots, std::numeric_limits<float>::max());
  out.cluster_far_max.assign(slots, std::numeric_limits<float>::lowest());
  for (int j = 0; j < out.k; ++j)
    for (int p = out.cluster_begin[static_cast<std::size_t>(j)]; p < out.cluster_begin[static_cast<std::size_t>(j) + 1]; ++p) {
      const std::size_t e = static_cast<std::size_t>(out.pose_entry[static_cast<std::size_t>(p)]);
      const std::size_t slot = static_cast<std::size_t>(j) * 2 + out.entry_kind[e];
      const vec3 lo = out.entry_box_min[e], hi = out.entry_box_max[e];
      const vec2 c = out.pose_centroid_start[static_cast<std::size_t>(p)];
      const float nx = std::clamp(c.x, lo.x, hi.x) - c.x, nz = std::clamp(c.y, lo.z, hi.z) - c.y;
      const float fx = std::max(std::abs(lo.x - c.x), std::abs(hi.x - c.x));
      const float fz = std::max(std::abs(lo.z - c.y), std::abs(hi.z - c.y));
      out.cluster_y_min[slot] = std::min(out.cluster_y_min[slot], lo.y);
      out.cluster_y_max[slot] = std::max(out.cluster_y_max[slot], hi.y);
      out.cluster_near_min[slot] = std::min(out.cluster_near_min[slot], std::sqrt(nx * nx + nz * nz));
      out.cluster_far_max[slot] = std::max(out.cluster_far_max[slot], std::sqrt(fx * fx + fz * fz));
    }
}

struct RefRetriever::Best {
  float cost = std::numeric_limits<float>::max();
  int pose = -1;
  float d_pose = 0.0f, d_target = 0.0f;
  int closest_offset = 0;
  float cos_h = 1.0f, sin_h = 0.0f;
  vec2 pos{0.0f};
  vec3 target_local{0.0f};  ///< The target in the candidate's root frame, body sizes.
};

RefRetriever::RefRetriever(const RefIndex& index)
    : index_(&index),
      centroid_d_(static_cast<std::size_t>(index.k)),
      order_(static_cast<std::size_t>(index.k)) {}

bool RefRetriever::cluster_may_hold(int j, float margin) const {
  const RefIndex& x = *index_;
  // Growing a box by `margin` moves its near distance down and its far distance up by at most
  // margin * sqrt(2) on the ground plane.
  const float grow = margin * 1.41422f;
  const float rho = std::sqrt(rho_sq_);
  for (int kind = 0; kind < 2; ++kind) {
    if (kind_ >= 0 && kind != kind_) continue;
    const std::size_t slot = static_cast<std::size_t>(j) * 2 + static_cast<std::size_t>(kind);
    if (target_n_.y >= x.cluster_y_min[slot] - margin && target_n_.y <= x.cluster_y_max[slot] + margin &&
        rho >= x.cluster_near_min[slot] - grow && rho <= x.cluster_far_max[slot] + grow)
      return true;
  }
  return false;
}

void RefRetriever::scan(int begin, int end, bool box_test, const RetrievalParams& params, Best& best,
                            RetrievalResult& out) const {
  const RefIndex& x = *index_;
  constexpr float kInvPoints = 1.0f / kPoseKeyPoints;
  const float margin = params.box_margin;
  const int w = x.hit_window_frames;
  for (int p = begin; p < end; ++p) {
    const std::size_t e = static_cast<std::size_t>(x.pose_entry[static_cast<std::size_t>(p)]);
    if ((kind_ >= 0 && x.entry_kind[e] != kind_) || (side_ >= 0 && x.entry_side[e] != side_)) continue;
    const vec3 lo = x.entry_box_min[e] - margin, hi = x.entry_box_max[e] + margin;
    if (box_test) {
      // Two exact necessary conditions that need no alignment, cheapest first: ground transforms
      // keep the target's height, and keep its ground distance to the pose's centroid (rho), so
      // the box must span that height and meet the circle of radius rho about the centroid.
      if (target_n_.y < lo.y || target_n_.y > hi.y) {
        ++out.candidates_rejected;
        continue;
      }
      const vec2 c = x.pose_centroid_start[static_cast<std::size_t>(p)];
      const float nx = std::clamp(c.x, lo.x, hi.x) - c.x, nz = std::clamp(c.y, lo.z, hi.z) - c.y;
      const float fx = std::max(std::abs(lo.x - c.x), std::abs(hi.x - c.x));
      const float fz = std::max(std::abs(lo.z - c.y), std::abs(hi.z - c.y));
      if (nx * nx + nz * nz > rho_sq_ || fx * fx + fz * fz < rho_sq_) {
        ++out.candidates_rejected;
        continue;
      }
    }
    float c = 0.0f, s = 0.0f;
    const float d2 = pose_cloud_distance_sq(q_pts_.data(), q_ss_, x.pose_pts.data() + static_cast<std::size_t>(p) * kPoseCloudFloats,
                                            x.pose_ss[static_cast<std::size_t>(p)], c, s);
    const float d_pose = std::sqrt(d2 * kInvPoints);
    // The pose term alone already loses: skip the target work.
    if (params.w_pose * d_pose >= best.cost) continue;
    // Alignment A (candidate -> current pose): heading from C and S, translation between centroids.
    const float r = std::sqrt(c * c + s * s);
    const float ch = r > 1e-12f ? c / r : 1.0f, sh = r > 1e-12f ? s / r : 0.0f;
    const vec2 bc = x.pose_centroid[static_cast<std::size_t>(p)];
    const vec2 pos = q_centroid_ - vec2(ch * bc.x + sh * bc.y, -sh * bc.x + ch * bc.y);
    // The target in the candidate's root frame: A^-1.
    const vec2 v = vec2(target_n_.x, target_n_.z) - pos;
    const vec3 local(ch * v.x - sh * v.y, target_n_.y, sh * v.x + ch * v.y);
    // ... and in the entry's start root frame, where its hit path and box are stored.
    const int offset = x.pose_offset[static_cast<std::size_t>(p)];
    const std::size_t f = static_cast<std::size_t>(x.entry_frames_begin[e] + offset);
    const float rc = x.frame_root_cos[f], rs = x.frame_root_sin[f];
    const vec2 rp = x.frame_root_pos[f];
    const vec3 t(rc * local.x + rs * local.z + rp.x, local.y, -rs * local.x + rc * local.z + rp.y);
    if (box_test && (t.x < lo.x || t.z < lo.z || t.x > hi.x || t.z > hi.z)) {
      ++out.candidates_rejected;
      continue;
    }
    ++out.candidates_scored;
    const int hit = x.entry_hit_offset[e];
    const int wlo = std::max(offset, hit - w), whi = std::min(x.entry_num_frames[e] - 1, hit + w);
    const std::size_t base = static_cast<std::size_t>(x.entry_frames_begin[e]);
    float best_t = std::numeric_limits<float>::max();
    int closest = hit;
    for (int i = wlo; i <= whi; ++i) {
      const vec3 d = x.frame_hit[base + static_cast<std::size_t>(i)] - t;
      const float dd = glm::dot(d, d);
      if (dd < best_t) {
        best_t = dd;
        closest = i;
      }
    }
    const float d_target = std::sqrt(best_t);
    const float cost = params.w_pose * d_pose + params.w_target * d_target;
    if (cost < best.cost) {
      best.cost = cost;
      best.pose = p;
      best.d_pose = d_pose;
      best.d_target = d_target;
      best.closest_offset = closest;
      best.cos_h = ch;
      best.sin_h = sh;
      best.pos = pos;
      best.target_local = local;
    }
  }
}

bool RefRetriever::retrieve(const RetrievalQuery& query, const RetrievalParams& params, RetrievalResult& out) {
  const RefIndex& x = *index_;
  out = RetrievalResult{};
  if (x.k == 0 || !(query.body_size_m > 0.0f)) return false;

  // Prepare the query in body sizes (eq. 1 for the target).
  const float inv = 1.0f / query.body_size_m;
  std::array<vec3, kPoseKeyPoints> kp;
  for (int i = 0; i < kPoseKeyPoints; ++i) kp[static_cast<std::size_t>(i)] = query.pose_key_points_m[static_cast<std::size_t>(i)] * inv;
  pose_cloud_pack(kp, q_pts_.data(), q_ss_, q_centroid_);
  target_n_ = query.target_m * inv;
  const vec2 rho = vec2(target_n_.x, target_n_.z) - q_centroid_;
  rho_sq_ = glm::dot(rho, rho);
  kind_ = query.kind ? static_cast<int>(*query.kind) : -1;
  side_ = query.side ? static_cast<int>(*query.side) : -1;

  // 1. Clusters by centroid distance. Only as many as are searched get ordered (a partial sort
  // per widening step), so the common case sorts a handful.
  float c = 0.0f, s = 0.0f;
  for (int j = 0; j < x.k; ++j) {
    centroid_d_[static_cast<std::size_t>(j)] = pose_cloud_distance_sq(
        q_pts_.data(), q_ss_, x.centroid_pts.data() + static_cast<std::size_t>(j) * kPoseCloudFloats,
        x.centroid_ss[static_cast<std::size_t>(j)], c, s);
    order_[static_cast<std::size_t>(j)] = j;
  }
  int ordered = 0;
  const auto order_up_to = [&](int n) {
    n = std::min(n, x.k);
    if (n <= ordered) return;
    std::partial_sort(order_.begin() + ordered, order_.begin() + n, order_.end(), [&](std::int32_t a, std::int32_t b) {
      const float da = centroid_d_[static_cast<std::size_t>(a)], db = centroid_d_[static_cast<std::size_t>(b)];
      return da != db ? da < db : a < b;
    });
    ordered = n;
  };
  order_up_to(1);
  out.cluster = order_[0];

  // 2-3. The nearest cluster; then the next widen_clusters; then further clusters in order of
  // distance, in growing steps, until one holds a candidate; clusters whose bounds rule out the
  // target are skipped whole.
  Best best;
  const auto scan_clusters = [&](int from, int to, bool box) {
    for (int i = from; i < to && i < x.k; ++i) {
      const int j = order_[static_cast<std::size_t>(i)];
      if (box && !cluster_may_hold(j, params.box_margin)) continue;
      // Triangle inequality: no pose of this cluster can beat the best so far.
      const float lower = std::sqrt(centroid_d_[static_cast<std::size_t>(j)] / kPoseKeyPoints) -
                          x.cluster_radius[static_cast<std::size_t>(j)];
      if (best.pose >= 0 && params.w_pose * lower >= best.cost) continue;
      if (box) ++out.clusters_searched;
      scan(x.cluster_begin[static_cast<std::size_t>(j)], x.cluster_begin[static_cast<std::size_t>(j) + 1], box, params,
           best, out);
    }
  };
  out.scope = RetrievalScope::kCluster;
  scan_clusters(0, 1, true);
  const int limit = params.max_clusters > 0 ? std::min(x.k, params.max_clusters) : x.k;
  const int widened = std::min(limit, 1 + std::max(0, params.widen_clusters));
  if (best.pose < 0) {
    out.scope = RetrievalScope::kWidened;
    order_up_to(widened);
    scan_clusters(1, widened, true);
  }
  for (int done = widened; best.pose < 0 && done < limit;) {
    out.scope = RetrievalScope::kAll;
    const int next = std::min(limit, 2 * done);
    order_up_to(next);
    scan_clusters(done, next, true);
    done = next;
  }
  if (best.pose < 0) {
    // No box holds the target: the best start from the nearest clusters, its hit brought as close
    // as it goes (the adaptation reaches what it can). All clusters only when those hold nothing
    // of the ordered kind.
    out.scope = RetrievalScope::kNoBoxFilter;
    out.capped = limit < x.k;
    scan_clusters(0, widened, false);
    // (The one change to the reference: none of the ordered kind in the nearest clusters goes on
    // in the widening's doubling steps, not straight to every cluster.)
    for (int done = widened; best.pose < 0 && done < x.k;) {
      const int next = std::min(x.k, 2 * done);
      order_up_to(next);
      scan_clusters(done, next, false);
      done = next;
    }
  }
  if (best.pose < 0) return false;

  const std::size_t p = static_cast<std::size_t>(best.pose);
  const std::size_t e = static_cast<std::size_t>(x.pose_entry[p]);
  const int start = x.entry_start_frame[e];
  out.entry = static_cast<int>(e);
  out.start_frame = start + x.pose_offset[p];
  out.hit_frame = start + x.entry_hit_offset[e];
  out.closest_frame = start + best.closest_offset;
  out.pose_distance = best.d_pose;
  out.target_distance = best.d_target;
  out.cost = best.cost;
  out.alignment.heading_rad = std::atan2(best.sin_h, best.cos_h);
  out.alignment.pos_m = best.pos * query.body_size_m;
  out.target_in_entry_m = best.target_local * x.entry_body_size_m[e];
  return true;
}


}  // namespace reference

namespace {

// Queries as the benchmark draws them: guard and wind-up poses of random entries with 1 cm of
// noise, fighters of 0.85-1.2 times the default size, targets knee to above head height, orders
// punch / kick / either, sometimes a side; plus a few targets out of reach.
std::vector<RetrievalQuery> random_queries(const FighterDatabase& db, int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const auto uniform = [&](float lo, float hi) {
    return lo + static_cast<float>(static_cast<double>(rng() >> 11) * (1.0 / 9007199254740992.0)) * (hi - lo);
  };
  std::vector<RetrievalQuery> out(static_cast<std::size_t>(count));
  for (std::size_t n = 0; n < out.size(); ++n) {
    RetrievalQuery& q = out[n];
    const FighterEntry& e = db.entries[static_cast<std::size_t>(rng() % db.entries.size())];
    const int frame = static_cast<int>(rng() % static_cast<std::uint64_t>(std::max(1, (e.hit_frame - e.start_frame) / 2)));
    q.body_size_m = 1.45f * uniform(0.85f, 1.2f);
    for (int i = 0; i < kPoseKeyPoints; ++i) {
      const vec3 noise(uniform(-0.01f, 0.01f), uniform(-0.01f, 0.01f), uniform(-0.01f, 0.01f));
      q.pose_key_points_m[static_cast<std::size_t>(i)] =
          (e.key_points[static_cast<std::size_t>(frame * kPoseKeyPoints + i)] + noise) * q.body_size_m;
    }
    const float s = q.body_size_m / 1.45f;
    q.target_m = vec3(uniform(-0.4f, 0.4f), uniform(0.5f, 1.8f), uniform(0.3f, 1.1f)) * s;
    if (n % 50 == 7) q.target_m = vec3(0.0f, 1.0f, 6.0f);  // out of every box
    const std::uint64_t order = rng() % 3;
    if (order == 1) q.kind = StrikeKind::kPunch;
    if (order == 2) q.kind = StrikeKind::kKick;
    if (rng() % 4 == 0) q.side = rng() % 2 == 0 ? StrikeSide::kLeft : StrikeSide::kRight;
  }
  return out;
}

void expect_same_answers(const FighterDatabase& db, const PoseClusterParams& cluster_params, const RetrievalParams& params,
                         int count, std::uint64_t seed) {
  PoseClusters clusters;
  pose_clusters_compute(db, cluster_params, clusters);
  reference::RefIndex ref_index;
  reference::fighter_retrieval_index_build(db, clusters, RetrievalIndexParams{}, ref_index);
  FighterRetrievalIndex index;
  fighter_retrieval_index_build(db, clusters, RetrievalIndexParams{}, index);
  reference::RefRetriever ref(ref_index);
  FighterRetriever fast(index);
  int scored_ref = 0, scored_fast = 0, differ = 0;
  const std::vector<RetrievalQuery> queries = random_queries(db, count, seed);
  for (std::size_t i = 0; i < queries.size(); ++i) {
    RetrievalResult a, b;
    const bool fa = ref.retrieve(queries[i], params, a);
    const bool fb = fast.retrieve(queries[i], params, b);
    ASSERT_EQ(fa, fb) << i;
    scored_ref += a.candidates_scored;
    scored_fast += b.candidates_scored;
    if (a.entry != b.entry || a.start_frame != b.start_frame || a.scope != b.scope || a.capped != b.capped) ++differ;
    EXPECT_EQ(a.entry, b.entry) << i;
    EXPECT_EQ(a.start_frame, b.start_frame) << i;
    EXPECT_EQ(a.closest_frame, b.closest_frame) << i;
    EXPECT_EQ(a.scope, b.scope) << i;
    EXPECT_EQ(a.capped, b.capped) << i;
    EXPECT_EQ(a.cluster, b.cluster) << i;
    EXPECT_NEAR(a.cost, b.cost, 1e-5f) << i;
    EXPECT_NEAR(a.alignment.heading_rad, b.alignment.heading_rad, 1e-5f) << i;
    if (differ > 5) break;
  }
  (void)scored_ref;
  (void)scored_fast;
}

TEST(RetrievalReference, SameAnswersAsThePlainScanOnTheDefaultLibrary) {
  FighterDatabase db;
  std::string error;
  ASSERT_TRUE(fighter_database_add_default_library(db, error)) << error;
  expect_same_answers(db, PoseClusterParams{}, RetrievalParams{}, 2000, 11);
  PoseClusterParams many;
  many.k = 40;
  expect_same_answers(db, many, RetrievalParams{}, 2000, 12);
}

TEST(RetrievalReference, SameAnswersAsThePlainScanOnASyntheticDatabase) {
  FighterDatabase seed;
  std::string error;
  ASSERT_TRUE(fighter_database_add_default_library(seed, error)) << error;
  const FighterDatabase db = fighter_database_synthetic(seed, 1500, 3);
  expect_same_answers(db, PoseClusterParams{}, RetrievalParams{}, 3000, 21);
  RetrievalParams capped;
  capped.max_clusters = 6;
  expect_same_answers(db, PoseClusterParams{}, capped, 1000, 22);
  RetrievalParams weights;
  weights.w_pose = 0.5f;
  weights.w_target = 2.0f;
  weights.box_margin = 0.05f;
  expect_same_answers(db, PoseClusterParams{}, weights, 1000, 23);
  RetrievalParams pose_only;
  pose_only.w_target = 0.0f;
  expect_same_answers(db, PoseClusterParams{}, pose_only, 500, 24);
}

}  // namespace
}  // namespace foresight

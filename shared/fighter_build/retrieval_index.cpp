#include "fighter_build/retrieval_index.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace foresight {

void fighter_retrieval_index_build(const FighterDatabase& db, const PoseClusters& clusters,
                                   const RetrievalIndexParams& params, FighterRetrievalIndex& out) {
  out = FighterRetrievalIndex{};
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

  // Candidate start poses grouped by cluster, kind and side (a counting sort keeps each group
  // contiguous and the order inside it deterministic); then each group sorted by the distance to
  // its cluster's centroid (stable: ties keep database order).
  struct Candidate {
    std::int32_t pose, entry, offset;
  };
  std::vector<Candidate> candidates;
  const std::size_t num_groups = static_cast<std::size_t>(out.k) * 4;
  std::vector<std::int32_t> counts(num_groups + 1, 0);
  const auto group_of = [&](int cluster, std::size_t e) {
    return static_cast<std::size_t>(cluster) * 4 + static_cast<std::size_t>(out.entry_kind[e]) * 2 +
           static_cast<std::size_t>(out.entry_side[e]);
  };
  int pose = 0;
  for (std::size_t e = 0; e < num_entries; ++e) {
    const FighterEntry& entry = db.entries[e];
    const int last_start = std::max(0, out.entry_hit_offset[e] - params.min_lead_frames);
    for (int i = 0; i < entry.num_frames(); ++i, ++pose) {
      if (i > last_start) continue;
      candidates.push_back({pose, static_cast<std::int32_t>(e), i});
      ++counts[group_of(clusters.assignment[static_cast<std::size_t>(pose)], e) + 1];
    }
  }
  std::partial_sum(counts.begin(), counts.end(), counts.begin());
  out.group_begin = counts;
  out.cluster_begin.resize(static_cast<std::size_t>(out.k) + 1);
  for (int j = 0; j <= out.k; ++j) out.cluster_begin[static_cast<std::size_t>(j)] = counts[static_cast<std::size_t>(j) * 4];
  const std::size_t m = candidates.size();
  std::vector<Candidate> slots(m);
  {
    std::vector<std::int32_t> fill(counts.begin(), counts.end() - 1);
    for (const Candidate& c : candidates) {
      const int cluster = clusters.assignment[static_cast<std::size_t>(c.pose)];
      slots[static_cast<std::size_t>(fill[group_of(cluster, static_cast<std::size_t>(c.entry))]++)] = c;
    }
  }
  // Distance of each candidate to its cluster's centroid, then the sort inside each group.
  std::vector<float> dc(m), residual(m);
  std::vector<vec2> arc(m);
  for (std::size_t g = 0; g < num_groups; ++g) {
    const std::size_t j = g / 4;
    for (int q = counts[g]; q < counts[g + 1]; ++q) {
      const Candidate& c = slots[static_cast<std::size_t>(q)];
      const FighterEntry& entry = db.entries[static_cast<std::size_t>(c.entry)];
      float pts[kPoseCloudFloats], ss = 0.0f, cs = 0.0f, sn = 0.0f;
      vec2 centroid;
      pose_cloud_pack(std::span<const vec3, kPoseKeyPoints>(
                          entry.key_points.data() + static_cast<std::size_t>(c.offset) * kPoseKeyPoints, kPoseKeyPoints),
                      pts, ss, centroid);
      const float d2 = pose_cloud_distance_sq(out.centroid_pts.data() + j * kPoseCloudFloats, out.centroid_ss[j], pts, ss, cs, sn);
      dc[static_cast<std::size_t>(q)] = std::sqrt(d2 / kPoseKeyPoints);
      // Heading aligning the pose onto the centroid, and the ground residual of that alignment.
      const double r = std::sqrt(static_cast<double>(cs) * cs + static_cast<double>(sn) * sn);
      arc[static_cast<std::size_t>(q)] = r > 1e-12 ? vec2(static_cast<float>(cs / r), static_cast<float>(sn / r)) : vec2(1.0f, 0.0f);
      double res2 = 0.0;  // sum |b_i - e^{i phi} m_i|^2 over the ground coordinates, in double
      {
        const float* mean = out.centroid_pts.data() + j * kPoseCloudFloats;
        const double ca = arc[static_cast<std::size_t>(q)].x, sa = arc[static_cast<std::size_t>(q)].y;
        for (int i = 0; i < kPoseKeyPoints; ++i) {
          const double mx = mean[i], mz = mean[2 * kPoseKeyPoints + i];
          const double dx = pts[i] - (ca * mx - sa * mz), dz = pts[2 * kPoseKeyPoints + i] - (sa * mx + ca * mz);
          res2 += dx * dx + dz * dz;
        }
      }
      residual[static_cast<std::size_t>(q)] = static_cast<float>(std::sqrt(res2) * 1.0001 + 1e-5);
    }
    std::vector<std::int32_t> perm(static_cast<std::size_t>(counts[g + 1] - counts[g]));
    std::iota(perm.begin(), perm.end(), counts[g]);
    std::stable_sort(perm.begin(), perm.end(), [&](std::int32_t a, std::int32_t b) {
      return dc[static_cast<std::size_t>(a)] < dc[static_cast<std::size_t>(b)];
    });
    std::vector<Candidate> sorted_c(perm.size());
    std::vector<float> sorted_d(perm.size()), sorted_r(perm.size());
    std::vector<vec2> sorted_a(perm.size());
    for (std::size_t i = 0; i < perm.size(); ++i) {
      sorted_c[i] = slots[static_cast<std::size_t>(perm[i])];
      sorted_d[i] = dc[static_cast<std::size_t>(perm[i])];
      sorted_r[i] = residual[static_cast<std::size_t>(perm[i])];
      sorted_a[i] = arc[static_cast<std::size_t>(perm[i])];
    }
    std::copy(sorted_c.begin(), sorted_c.end(), slots.begin() + counts[g]);
    std::copy(sorted_d.begin(), sorted_d.end(), dc.begin() + counts[g]);
    std::copy(sorted_r.begin(), sorted_r.end(), residual.begin() + counts[g]);
    std::copy(sorted_a.begin(), sorted_a.end(), arc.begin() + counts[g]);
  }

  out.pose_pts.assign(m * kPoseCloudPaddedFloats, 0.0f);
  out.pose_frame.resize(m);
  out.pose_ss.resize(m);
  out.pose_centroid.resize(m);
  out.pose_entry.resize(m);
  out.pose_offset.resize(m);
  out.pose_centroid_start.resize(m);
  out.pose_bounds.resize(m);
  for (std::size_t slot = 0; slot < m; ++slot) {
    const Candidate& c = slots[slot];
    const std::size_t e = static_cast<std::size_t>(c.entry);
    const FighterEntry& entry = db.entries[e];
    float pts[kPoseCloudFloats];
    pose_cloud_pack(std::span<const vec3, kPoseKeyPoints>(
                        entry.key_points.data() + static_cast<std::size_t>(c.offset) * kPoseKeyPoints, kPoseKeyPoints),
                    pts, out.pose_ss[slot], out.pose_centroid[slot]);
    pose_cloud_pad(pts, out.pose_pts.data() + slot * kPoseCloudPaddedFloats);
    out.pose_entry[slot] = c.entry;
    out.pose_offset[slot] = c.offset;
    // The pose's ground centroid carried into the entry's start frame (for the ring test).
    const std::size_t f = static_cast<std::size_t>(out.entry_frames_begin[e] + c.offset);
    const vec2 b = out.pose_centroid[slot];
    const float rc = out.frame_root_cos[f], rs = out.frame_root_sin[f];
    const vec2 cs = vec2(rc * b.x + rs * b.y, -rs * b.x + rc * b.y) + out.frame_root_pos[f];
    out.pose_centroid_start[slot] = cs;
    RetrievalPoseBounds& pb = out.pose_bounds[slot];
    const vec3 lo = out.entry_box_min[e], hi = out.entry_box_max[e];
    pb.y_lo = lo.y;
    pb.y_hi = hi.y;
    pb.x_lo = lo.x - cs.x;
    pb.x_hi = hi.x - cs.x;
    pb.z_lo = lo.z - cs.y;
    pb.z_hi = hi.z - cs.y;
    // The d_target window of this start, as scan() takes it.
    const int hit = out.entry_hit_offset[e];
    const int wlo = std::max(c.offset, hit - params.hit_window_frames);
    const int whi = std::min(out.entry_num_frames[e] - 1, hit + params.hit_window_frames);
    RetrievalPoseFrame& pf = out.pose_frame[slot];
    pf.root_cos = rc;
    pf.root_sin = rs;
    pf.root_pos = out.frame_root_pos[f];
    pf.hit_lo = vec3(std::numeric_limits<float>::max());
    pf.hit_hi = vec3(std::numeric_limits<float>::lowest());
    pb.hit_r_lo = pb.hit_y_lo = std::numeric_limits<float>::max();
    pb.hit_r_hi = pb.hit_y_hi = std::numeric_limits<float>::lowest();
    for (int i = wlo; i <= whi; ++i) {
      const vec3 h = out.frame_hit[static_cast<std::size_t>(out.entry_frames_begin[e] + i)];
      pf.hit_lo = glm::min(pf.hit_lo, h);
      pf.hit_hi = glm::max(pf.hit_hi, h);
      const float r = glm::length(vec2(h.x, h.z) - cs);
      pb.hit_r_lo = std::min(pb.hit_r_lo, r);
      pb.hit_r_hi = std::max(pb.hit_r_hi, r);
      pb.hit_y_lo = std::min(pb.hit_y_lo, h.y);
      pb.hit_y_hi = std::max(pb.hit_y_hi, h.y);
    }
    pb.centroid_distance = dc[slot];
    pb.sum_sq_xz = out.pose_ss[slot];
    pb.entry = c.entry;
    // phi - f as a rotation: (cos phi, sin phi) times (cos f, -sin f).
    const vec2 phi = arc[slot];
    pb.arc_cos = phi.x * rc + phi.y * rs;
    pb.arc_sin = phi.y * rc - phi.x * rs;
    pb.residual_xz = residual[slot];
  }

  // Per-cluster bounds of the box tests, per kind.
  const std::size_t kinds = static_cast<std::size_t>(out.k) * 2;
  out.cluster_y_min.assign(kinds, std::numeric_limits<float>::max());
  out.cluster_y_max.assign(kinds, std::numeric_limits<float>::lowest());
  out.cluster_near_min.assign(kinds, std::numeric_limits<float>::max());
  out.cluster_far_max.assign(kinds, std::numeric_limits<float>::lowest());
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

void fighter_retrieval_prepare(const FighterDatabase& db, const PoseClusterParams& cluster_params,
                               const RetrievalIndexParams& index_params, const std::filesystem::path& cache_dir,
                               FighterRetrievalIndex& out, ClusterCacheStatus* status, std::string* warning) {
  PoseClusters clusters;
  ClusterCacheStatus s{};
  std::string w;
  pose_clusters_load_or_compute(db, cluster_params, cache_dir, clusters, s, w);
  fighter_retrieval_index_build(db, clusters, index_params, out);
  if (status != nullptr) *status = s;
  if (warning != nullptr) *warning = w;
}

}  // namespace foresight

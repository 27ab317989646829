#include "fighter/retrieval.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numeric>

namespace foresight {

std::string_view retrieval_scope_name(RetrievalScope scope) {
  switch (scope) {
    case RetrievalScope::kCluster: return "cluster";
    case RetrievalScope::kWidened: return "widened";
    case RetrievalScope::kAll: return "all";
    case RetrievalScope::kNoBoxFilter: return "no box filter";
  }
  return "?";
}

struct FighterRetriever::Best {
  float cost = std::numeric_limits<float>::max();
  int pose = -1;
  float d_pose = 0.0f, d_target = 0.0f;
  int closest_offset = 0;
  float cos_h = 1.0f, sin_h = 0.0f;
  vec2 pos{0.0f};
  vec3 target_local{0.0f};  ///< The target in the candidate's root frame, body sizes.
};

FighterRetriever::FighterRetriever(const FighterRetrievalIndex& index)
    : index_(&index),
      centroid_d_(static_cast<std::size_t>(index.k)),
      centroid_c_(static_cast<std::size_t>(index.k)),
      centroid_s_(static_cast<std::size_t>(index.k)),
      order_(static_cast<std::size_t>(index.k)) {}

bool FighterRetriever::cluster_may_hold(int j, float margin) const {
  const FighterRetrievalIndex& x = *index_;
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

namespace {

// Rounding slack of the lower bounds (body sizes): the aligned distance loses ~1e-4 to
// cancellation near zero, so a bound is lowered by this before it may rule a pose out.
constexpr float kBoundSlack = 1e-3f;

}  // namespace

void FighterRetriever::align(int p, Aligned& a) const {
  const FighterRetrievalIndex& x = *index_;
  float c = 0.0f, s = 0.0f;
  const float d2 = pose_cloud_distance_sq_padded(q_pad_.data(), q_ss_,
                                                 x.pose_pts.data() + static_cast<std::size_t>(p) * kPoseCloudPaddedFloats,
                                                 x.pose_ss[static_cast<std::size_t>(p)], c, s);
  a.pose = p;
  a.d_pose = std::sqrt(d2 * (1.0f / kPoseKeyPoints));
  // Alignment A (candidate -> current pose): heading from C and S, translation between centroids.
  const float r = std::sqrt(c * c + s * s);
  const float ch = r > 1e-12f ? c / r : 1.0f, sh = r > 1e-12f ? s / r : 0.0f;
  const vec2 bc = x.pose_centroid[static_cast<std::size_t>(p)];
  a.cos_h = ch;
  a.sin_h = sh;
  a.pos = q_centroid_ - vec2(ch * bc.x + sh * bc.y, -sh * bc.x + ch * bc.y);
  // The target in the candidate's root frame: A^-1.
  const vec2 v = vec2(target_n_.x, target_n_.z) - a.pos;
  a.local = vec3(ch * v.x - sh * v.y, target_n_.y, sh * v.x + ch * v.y);
  // ... and in the entry's start root frame, where its hit path and box are stored.
  const RetrievalPoseFrame& pf = x.pose_frame[static_cast<std::size_t>(p)];
  const float rc = pf.root_cos, rs = pf.root_sin;
  a.t = vec3(rc * a.local.x + rs * a.local.z + pf.root_pos.x, a.local.y, -rs * a.local.x + rc * a.local.z + pf.root_pos.y);
}

void FighterRetriever::gather(int j, bool box_test, const RetrievalParams& params, Best& best,
                              RetrievalResult& out) {
  const FighterRetrievalIndex& x = *index_;
  // The lower bounds below (used once a candidate is in hand, from this cluster or an earlier one
  // of the step) hold for non-negative weights; the walk's needs w_pose > 0.
  const bool prune = params.w_pose > 0.0f && params.w_target >= 0.0f;
  const float dqc = std::sqrt(centroid_d_[static_cast<std::size_t>(j)] * (1.0f / kPoseKeyPoints));
  const float margin = params.box_margin;
  const float ty = target_n_.y;
  // The heading bound (RetrievalPoseBounds::arc_*): the target's direction about a start's
  // centroid is arc_base * arc within +-delta, sin(delta) = |q_xz| residual / |z_qm|.
  const float cj = centroid_c_[static_cast<std::size_t>(j)], sj = centroid_s_[static_cast<std::size_t>(j)];
  const float zr = std::sqrt(cj * cj + sj * sj);
  const bool arc_test = box_test && zr > 1e-6f && rho_ > 0.0f;
  const float inv_zr = zr > 1e-6f ? 1.0f / zr : 0.0f;
  const vec2 arc_base = arc_test ? vec2(u_dir_.x * cj - u_dir_.y * sj, u_dir_.x * sj + u_dir_.y * cj) * inv_zr : vec2(1.0f, 0.0f);
  const float ratio_scale = q_norm_xz_ * inv_zr;
  for (int kind = 0; kind < 2; ++kind) {
    if (kind_ >= 0 && kind != kind_) continue;
    for (int side = 0; side < 2; ++side) {
      if (side_ >= 0 && side != side_) continue;
      const std::size_t g = static_cast<std::size_t>(j) * 4 + static_cast<std::size_t>(kind) * 2 + static_cast<std::size_t>(side);
      // Nearest the query's centroid distance first, outwards: the first survivors are likely
      // the best, and once one is in hand the triangle inequality through the centroid
      // (d_pose >= |d(q, centroid) - d(b, centroid)|) ends the walk.
      const int begin = x.group_begin[g], end = x.group_begin[g + 1];
      const RetrievalPoseBounds* first = x.pose_bounds.data();
      int right = static_cast<int>(
          std::partition_point(first + begin, first + end, [dqc](const RetrievalPoseBounds& r) { return r.centroid_distance < dqc; }) - first);
      int left = right - 1;
      while (left >= begin || right < end) {
        const float gl = left >= begin ? dqc - first[left].centroid_distance : std::numeric_limits<float>::max();
        const float gr = right < end ? first[right].centroid_distance - dqc : std::numeric_limits<float>::max();
        const bool take_left = gl <= gr;
        const int p = take_left ? left-- : right++;
        if (prune && best.pose >= 0 && params.w_pose * ((take_left ? gl : gr) - kBoundSlack) >= best.cost) {
          out.candidates_bounded += (left - begin + 1) + (end - right) + 1;
          break;
        }
        const RetrievalPoseBounds& b = x.pose_bounds[static_cast<std::size_t>(p)];
        if (box_test) {
          // Two exact necessary conditions that need no alignment, cheapest first: ground
          // transforms keep the target's height, and keep its ground distance to the pose's
          // centroid (rho), so the box must span that height and meet the circle of radius rho
          // about the centroid (the box is stored relative to it).
          if (ty < b.y_lo - margin || ty > b.y_hi + margin) {
            ++out.candidates_rejected;
            continue;
          }
          const float xl = b.x_lo - margin, xh = b.x_hi + margin, zl = b.z_lo - margin, zh = b.z_hi + margin;
          const float nx = std::clamp(0.0f, xl, xh), nz = std::clamp(0.0f, zl, zh);
          const float fx = std::max(-xl, xh), fz = std::max(-zl, zh);
          if (nx * nx + nz * nz > rho_sq_ || fx * fx + fz * fz < rho_sq_) {
            ++out.candidates_rejected;
            continue;
          }
          // Then the arc of that circle the alignment's heading can reach: it lies in the disc of
          // radius chord = rho * 2 sin(delta / 2) about its middle point, so a box farther than
          // that from the middle cannot hold the target. With x = sin^2 delta (delta <= 90
          // degrees), chord^2 = rho^2 2 (1 - sqrt(1 - x)) <= rho^2 (x + x^2): no square root;
          // the slack covers rounding (1e-4 body sizes on the chord).
          const float ratio = ratio_scale * b.residual_xz;
          if (arc_test && ratio < 0.999f) {
            const float sin2 = ratio * ratio;
            const float chord_sq = rho_sq_ * (sin2 + sin2 * sin2) * 1.0021f + 2.9e-4f * rho_ + 1e-8f;
            const float mx = rho_ * (arc_base.x * b.arc_cos - arc_base.y * b.arc_sin);
            const float mz = rho_ * (arc_base.x * b.arc_sin + arc_base.y * b.arc_cos);
            const float ax = std::clamp(mx, xl, xh) - mx, az = std::clamp(mz, zl, zh) - mz;
            if (ax * ax + az * az > chord_sq) {
              ++out.candidates_rejected;
              continue;
            }
          }
        }
        if (prune && best.pose >= 0) {
          // Before aligning: d_pose from the walk's gap, d_target from the ring and the height.
          const float dr = std::max(0.0f, std::max(b.hit_r_lo - rho_, rho_ - b.hit_r_hi));
          const float dy = std::max(0.0f, std::max(b.hit_y_lo - ty, ty - b.hit_y_hi));
          const float lb = params.w_pose * std::max(0.0f, std::abs(dqc - b.centroid_distance) - kBoundSlack) +
                           params.w_target * std::max(0.0f, std::sqrt(dr * dr + dy * dy) - kBoundSlack);
          if (lb >= best.cost) {
            ++out.candidates_bounded;
            continue;
          }
        }
        Aligned a;
        align(p, a);
        const std::size_t e = static_cast<std::size_t>(b.entry);
        const vec3 t = a.t;
        const RetrievalPoseFrame& pf = x.pose_frame[static_cast<std::size_t>(p)];
        if (box_test) {
          const vec3 lo = x.entry_box_min[e] - margin, hi = x.entry_box_max[e] + margin;
          if (t.x < lo.x || t.z < lo.z || t.x > hi.x || t.z > hi.z) {
            ++out.candidates_rejected;
            continue;
          }
        }
        // Its cost is at least w_pose d_pose + w_target (distance from t to the window's box).
        const vec3 gap = glm::max(glm::max(pf.hit_lo - t, t - pf.hit_hi), vec3(0.0f));
        const float lb_target = std::max(0.0f, std::sqrt(glm::dot(gap, gap)) - kBoundSlack);
        evaluate(a, params.w_pose * a.d_pose + params.w_target * lb_target, params, best, out);
      }
    }
  }
}

void FighterRetriever::evaluate(const Aligned& a, float lower, const RetrievalParams& params, Best& best,
                                RetrievalResult& out) const {
  const FighterRetrievalIndex& x = *index_;
  const int w = x.hit_window_frames;
  // The bound holds for non-negative weights (the defaults are 1 and 1).
  if (params.w_pose >= 0.0f && params.w_target >= 0.0f && lower >= best.cost) {
    ++out.candidates_bounded;
    return;
  }
  // The pose term alone already loses: skip the target work.
  if (params.w_pose * a.d_pose >= best.cost) return;
  ++out.candidates_scored;
  const int p = a.pose;
  const std::size_t e = static_cast<std::size_t>(x.pose_bounds[static_cast<std::size_t>(p)].entry);
  const int offset = x.pose_offset[static_cast<std::size_t>(p)];
  const int hit = x.entry_hit_offset[e];
  const int wlo = std::max(offset, hit - w), whi = std::min(x.entry_num_frames[e] - 1, hit + w);
  const std::size_t base = static_cast<std::size_t>(x.entry_frames_begin[e]);
  float best_t = std::numeric_limits<float>::max();
  int closest = hit;
  for (int i = wlo; i <= whi; ++i) {
    const vec3 d = x.frame_hit[base + static_cast<std::size_t>(i)] - a.t;
    const float dd = glm::dot(d, d);
    if (dd < best_t) {
      best_t = dd;
      closest = i;
    }
  }
  const float d_target = std::sqrt(best_t);
  const float cost = params.w_pose * a.d_pose + params.w_target * d_target;
  if (cost < best.cost || (cost == best.cost && p < best.pose)) {
    best.cost = cost;
    best.pose = p;
    best.d_pose = a.d_pose;
    best.d_target = d_target;
    best.closest_offset = closest;
    best.cos_h = a.cos_h;
    best.sin_h = a.sin_h;
    best.pos = a.pos;
    best.target_local = a.local;
  }
}

bool FighterRetriever::retrieve(const RetrievalQuery& query, const RetrievalParams& params, RetrievalResult& out) {
  const FighterRetrievalIndex& x = *index_;
  out = RetrievalResult{};
  if (x.k == 0 || !(query.body_size_m > 0.0f)) return false;

  // Prepare the query in body sizes (eq. 1 for the target).
  const float inv = 1.0f / query.body_size_m;
  std::array<vec3, kPoseKeyPoints> kp;
  for (int i = 0; i < kPoseKeyPoints; ++i) kp[static_cast<std::size_t>(i)] = query.pose_key_points_m[static_cast<std::size_t>(i)] * inv;
  pose_cloud_pack(kp, q_pts_.data(), q_ss_, q_centroid_);
  pose_cloud_pad(q_pts_.data(), q_pad_.data());
  target_n_ = query.target_m * inv;
  const vec2 rho = vec2(target_n_.x, target_n_.z) - q_centroid_;
  rho_sq_ = glm::dot(rho, rho);
  rho_ = std::sqrt(rho_sq_);
  u_dir_ = rho_ > 0.0f ? rho / rho_ : vec2(1.0f, 0.0f);
  q_norm_xz_ = std::sqrt(q_ss_);
  kind_ = query.kind ? static_cast<int>(*query.kind) : -1;
  side_ = query.side ? static_cast<int>(*query.side) : -1;

  // 1. Clusters by centroid distance. Only as many as are searched get ordered (a partial sort
  // per widening step), so the common case sorts a handful.
  float c = 0.0f, s = 0.0f;
  for (int j = 0; j < x.k; ++j) {
    centroid_d_[static_cast<std::size_t>(j)] = pose_cloud_distance_sq(
        q_pts_.data(), q_ss_, x.centroid_pts.data() + static_cast<std::size_t>(j) * kPoseCloudFloats,
        x.centroid_ss[static_cast<std::size_t>(j)], c, s);
    centroid_c_[static_cast<std::size_t>(j)] = c;
    centroid_s_[static_cast<std::size_t>(j)] = s;
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
  // A step gathers the start poses of its clusters that pass the alignment-free tests, then costs
  // them best first (evaluate); the step's answer is the best of all of them, as a plain scan.
  const auto scan_clusters = [&](int from, int to, bool box) {
    for (int i = from; i < to && i < x.k; ++i) {
      const int j = order_[static_cast<std::size_t>(i)];
      if (box && !cluster_may_hold(j, params.box_margin)) continue;
      if (box) ++out.clusters_searched;
      gather(j, box, params, best, out);
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
    // None of the ordered kind there: on through the rest in the same doubling steps, nearest
    // first, until a step holds one.
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

}  // namespace foresight

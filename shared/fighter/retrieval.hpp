#pragma once
// Motion retrieval (paper 3.3): given the fighter's current pose and a target, the database entry
// and start frame to play, and the alignment that places it.
//
// Everything is compared in body sizes, which is the paper's eq. 1 applied per entry: the target
// c (fighter root frame, metres) becomes c / size_character, each entry's hit path is stored as
// path / size_actor, and the current pose's key points are divided by the fighter's size (the
// key-point cloud is what the paper's retargeting of q(t) onto the actor is needed for).
//
// Steps of retrieve():
//  1. the cluster whose centroid is nearest the current pose (aligned distance);
//  2. each candidate start pose of that cluster (a frame at least min_lead_frames before its
//     entry's hit, of the ordered kind and side) is aligned onto the current pose (rotation about
//     Y + ground translation, closed form); the target is carried into the candidate's frame and
//     the candidate is dropped when the entry's hit box (grown by box_margin) cannot contain it;
//  3. the survivor minimising w_pose * d_pose + w_target * d_target wins, d_pose the RMS key-point
//     distance, d_target the distance from the target to the hit path around the hit frame.
// When every candidate of the cluster is dropped, the search widens to the next widen_clusters
// nearest clusters, then on through the rest, nearest first in doubling steps, until a step finds
// a candidate (so "all" only when nothing nearer holds one), then (the target is out of every box)
// back to the nearest and widened clusters without the box test (and, when those hold nothing of
// the ordered kind, on in the same doubling steps); the result says which (scope), like Detour's
// partial-result status. Clusters whose per-cluster bounds rule the target out are skipped whole.
//
// How a step runs (the answer is the plain scan's: the best survivor of the step's clusters):
// gather() walks each ordered kind/side group of a cluster outwards from the query's distance to
// the centroid (groups are sorted by their poses' distance to it); it drops poses by tests that
// need no alignment (height, the ring of ground distance rho, the arc of it that the heading bound
// allows) and, once a candidate is in hand, by lower bounds (triangle inequality through the
// centroid for d_pose, the ring and height for d_target; the walk ends when the first alone loses);
// the rest are aligned and box-tested, and evaluate() costs a survivor unless w_pose d_pose +
// w_target (distance from the placed target to its hit window's box) already loses.
//
// Why d_target uses the hit path only around the hit (hit_window_frames) and not the whole
// trajectory the paper names: a kick's foot passes through every low height on its way up, so a
// whole-trajectory minimum would answer a low target with a high kick; the adaptation moves the
// effector at the hit time, so the hit's neighbourhood is what it has to bend.
#include "fighter/pose_cloud.hpp"
#include "fighter/strike_kind.hpp"
#include "math/types.hpp"

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace foresight {

/// Per start pose, what the alignment-free filters read, in one 64-byte record (gather() streams
/// these and touches the cloud only for poses that survive them). Boxes are the entry's hit box
/// (start root frame, body sizes, not grown) with x and z relative to the pose's centroid carried
/// into that frame, so the ring test is about the origin.
struct RetrievalPoseBounds {
  float y_lo = 0.0f, y_hi = 0.0f;  ///< The box's height range.
  float x_lo = 0.0f, x_hi = 0.0f, z_lo = 0.0f, z_hi = 0.0f;  ///< Its ground extent about the centroid.
  float centroid_distance = 0.0f;  ///< RMS distance to its cluster's centroid (body sizes).
  std::int32_t entry = 0;
  /// The heading bound: (arc_cos, arc_sin) is the rotation phi - f, phi the heading aligning this
  /// pose onto its cluster's centroid, f its frame's heading in the entry's start frame;
  /// residual_xz is sqrt(sum |e_i|^2) of the ground residual after that alignment (a few ulps
  /// high). The query's heading onto this pose is within asin(|q_xz| residual_xz / |z_qm|) of
  /// (its heading onto the centroid) + phi, so the target lies on a short arc of the ring.
  float arc_cos = 1.0f, arc_sin = 0.0f, residual_xz = 0.0f;
  float sum_sq_xz = 0.0f;  ///< The centred cloud's sum(x^2 + z^2) (as pose_ss).
  /// Ground distance from the centroid (start frame) to the hit path over this start's d_target
  /// window, and the path's height range there: with the target's rho and height they bound
  /// d_target from below with no alignment (any heading keeps rho). Loose where a box holds the
  /// target, tight where none does (the no-box fallback).
  float hit_r_lo = 0.0f, hit_r_hi = 0.0f, hit_y_lo = 0.0f, hit_y_hi = 0.0f;
};

/// Per start pose, what placing the target needs once the pose is aligned (read only for poses
/// that pass the filters): its frame's root placement in the entry's start frame, and the box of
/// the hit path over its d_target window (start root frame, body sizes), whose distance to the
/// placed target bounds d_target from below.
struct RetrievalPoseFrame {
  float root_cos = 1.0f, root_sin = 0.0f;
  vec2 root_pos{0.0f};
  vec3 hit_lo{0.0f}, hit_hi{0.0f};
  float pad_[2] = {0.0f, 0.0f};
};

/// The retrieval's hot data in structure-of-arrays form, built once (offline) from a database and
/// its clusters. Only poses that can start a strike are kept, grouped by cluster, inside a cluster
/// by kind and side (group g = cluster * 4 + kind * 2 + side; only the ordered groups are read),
/// inside a group nearest its cluster's centroid first.
struct FighterRetrievalIndex {
  int k = 0;
  std::vector<float> centroid_pts;  ///< [c * kPoseCloudFloats ...]
  std::vector<float> centroid_ss;
  std::vector<std::int32_t> cluster_begin;  ///< k + 1 offsets into the pose arrays.
  std::vector<std::int32_t> group_begin;    ///< 4k + 1 offsets: cluster, kind, side.
  /// Per cluster and kind ([c * 2 + kind]), bounds over its start poses for skipping a whole
  /// cluster when searching all of them: the height range of the members' hit boxes, and the
  /// least near / greatest far ground distance from a member's centroid to its box (the box
  /// tests below, taken over the cluster; empty clusters hold an empty range).
  std::vector<float> cluster_y_min, cluster_y_max, cluster_near_min, cluster_far_max;
  // Candidate start poses, cluster by cluster (group by group).
  std::vector<RetrievalPoseBounds> pose_bounds;
  std::vector<float> pose_pts;  ///< [p * kPoseCloudPaddedFloats ...], centred, padded to 16 points.
  std::vector<float> pose_ss;
  std::vector<RetrievalPoseFrame> pose_frame;
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

struct RetrievalQuery {
  /// The fighter's current key points, its root frame, metres (fighter_key_points_m).
  std::array<vec3, kPoseKeyPoints> pose_key_points_m{};
  float body_size_m = 1.0f;  ///< The fighter's FighterRig::body_size_m. > 0.
  vec3 target_m{0.0f};       ///< Where to hit, in the fighter's root frame, metres.
  std::optional<StrikeKind> kind;  ///< The supervisor's order; none: any.
  std::optional<StrikeSide> side;
};

struct RetrievalParams {
  float w_pose = 1.0f;      ///< Weight of d_pose (RMS key-point distance, body sizes).
  float w_target = 1.0f;    ///< Weight of d_target (body sizes).
  float box_margin = 0.15f; ///< Hit boxes grow by this (body sizes) before the containment test.
  int widen_clusters = 8;   ///< Further clusters searched before all of them.
  /// Budget: stop widening after this many clusters (0: no cap, search on to all of them) and
  /// answer as if no box held the target (RetrievalResult::capped says so). Bounds the worst case
  /// on large databases, where a target no nearby start pose can reach sends the search far.
  int max_clusters = 0;
};

enum class RetrievalScope : std::uint8_t {
  kCluster,     ///< Found in the nearest cluster (the paper's case).
  kWidened,     ///< In one of the next widen_clusters nearest clusters.
  kAll,         ///< Further clusters, nearest first, until one held a candidate (up to all).
  kNoBoxFilter, ///< No hit box could contain the target: best of the nearest clusters without the box test.
};
std::string_view retrieval_scope_name(RetrievalScope scope);

struct RetrievalResult {
  int entry = -1;          ///< Into FighterDatabase::entries; -1: nothing of that kind/side.
  int start_frame = -1;    ///< Take frame to start playing from.
  int hit_frame = -1;      ///< Take frame of the annotated hit.
  int closest_frame = -1;  ///< Take frame where the hit path passes nearest the target.
  /// Carries the entry's root frame at start_frame onto the fighter's root frame, fighter metres
  /// (the clip itself still needs retargeting to the fighter's size).
  Placement alignment;
  vec3 target_in_entry_m{0.0f};  ///< The scaled target c_r in the entry's root frame at start_frame, actor metres.
  float pose_distance = 0.0f;    ///< Body sizes (RMS over the key points).
  float target_distance = 0.0f;  ///< Body sizes; times the fighter's size: metres.
  float cost = 0.0f;
  int cluster = -1;              ///< The nearest cluster.
  RetrievalScope scope = RetrievalScope::kCluster;
  int candidates_scored = 0;     ///< Poses whose cost was computed.
  int candidates_rejected = 0;   ///< Poses dropped by the box test.
  int clusters_searched = 0;     ///< Clusters whose poses were looked at with the box test.
  int candidates_bounded = 0;    ///< Poses past the box test never costed: their lower bound could not win.
  bool capped = false;           ///< max_clusters stopped the widening before every cluster was searched.
  bool found() const { return entry >= 0; }
};

/// Runs queries against one index. Holds the per-query scratch (sized once here), so retrieve()
/// never allocates; one retriever per thread.
class FighterRetriever {
 public:
  explicit FighterRetriever(const FighterRetrievalIndex& index);
  /// False (out.entry = -1) for an empty index, body_size_m <= 0, or when no entry has the ordered
  /// kind and side.
  bool retrieve(const RetrievalQuery& query, const RetrievalParams& params, RetrievalResult& out);

 private:
  struct Best;
  struct Aligned {  ///< A gathered pose, aligned.
    std::int32_t pose;
    float d_pose, cos_h, sin_h;
    vec2 pos;
    vec3 local, t;  ///< The target in the pose's root frame / the entry's start frame, body sizes.
  };
  /// Searches `cluster` (see the top of this file), handing each aligned survivor of the box
  /// test to evaluate().
  void gather(int cluster, bool box_test, const RetrievalParams& params, Best& best, RetrievalResult& out);
  /// Costs an aligned survivor unless `lower` (a lower bound of its cost) cannot beat the best.
  void evaluate(const Aligned& a, float lower, const RetrievalParams& params, Best& best, RetrievalResult& out) const;
  /// Aligns start pose p onto the query and places the target in its entry's start frame.
  void align(int p, Aligned& a) const;
  /// False when no start pose of cluster j can pass the box test (per-cluster bounds).
  bool cluster_may_hold(int j, float margin) const;

  const FighterRetrievalIndex* index_;
  std::vector<float> centroid_d_;
  std::vector<float> centroid_c_, centroid_s_;  ///< C and S of the query onto each centroid.
  std::vector<std::int32_t> order_;
  // The prepared query.
  alignas(16) std::array<float, kPoseCloudPaddedFloats> q_pad_{};
  std::array<float, kPoseCloudFloats> q_pts_{};
  float q_ss_ = 0.0f;
  vec2 q_centroid_{0.0f};
  vec3 target_n_{0.0f};
  float rho_sq_ = 0.0f;  ///< Squared ground distance from the target to the pose's centroid.
  float rho_ = 0.0f;
  float q_norm_xz_ = 0.0f;  ///< sqrt(q_ss_).
  vec2 u_dir_{1.0f, 0.0f};  ///< (target - pose centroid) on the ground, unit (or (1, 0) when rho is 0).
  int kind_ = -1, side_ = -1;
};

}  // namespace foresight

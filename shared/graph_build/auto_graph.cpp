#include "graph_build/auto_graph.hpp"

#include "anim/fk.hpp"
#include "graph_build/graph_edit.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <tuple>

namespace foresight {
namespace {

// A window's point cloud, ready for the closed-form alignment: ground coordinates centred on the
// cloud's ground centroid (so the optimal translation is implicit), heights as they are.
struct WindowCloud {
  std::vector<float> u, v, y;  // SoA: the inner products below vectorise.
  float self_xz = 0.0f;        // sum of u^2 + v^2
};

struct ClipFrames {
  int num_windows = 0;  // windows start at frames 0, stride, 2*stride ... with a full window
  std::vector<WindowCloud> windows;
};

// Ground coordinates moved to the cloud's ground centroid (so the best translation is implicit).
void centre(WindowCloud& w) {
  float cu = 0, cv = 0;
  for (size_t i = 0; i < w.u.size(); ++i) cu += w.u[i], cv += w.v[i];
  cu /= static_cast<float>(w.u.size());
  cv /= static_cast<float>(w.u.size());
  for (size_t i = 0; i < w.u.size(); ++i) {
    w.u[i] -= cu;
    w.v[i] -= cv;
    w.self_xz += w.u[i] * w.u[i] + w.v[i] * w.v[i];
  }
}

ClipFrames clouds_of(const Skeleton& skeleton, const Clip& clip, const std::vector<int>& joints,
                     const AutoGraphOptions& o) {
  std::vector<vec3> pos;
  fk_clip_positions(skeleton, clip, pos);
  const int n = skeleton.num_joints();
  ClipFrames out;
  for (int start = 0; start + o.window_frames <= clip.num_frames; start += o.candidate_stride) {
    WindowCloud w;
    for (int f = start; f < start + o.window_frames; f += o.window_stride)
      for (int j : joints) {
        const vec3 p = pos[static_cast<size_t>(f) * n + j];
        w.u.push_back(p.x);
        w.v.push_back(p.z);
        w.y.push_back(p.y);
      }
    centre(w);
    out.windows.push_back(std::move(w));
  }
  out.num_windows = static_cast<int>(out.windows.size());
  return out;
}

// Squared distance under the best rotation about Y (translation is absorbed by the centring):
// sum|a|^2 + sum|b|^2 - 2 * max_theta sum a . R(theta) b, and max = sqrt(S^2 + C^2) with
// S = sum a.b and C = sum a x b in the ground plane. Heights are compared directly.
float aligned_distance(const WindowCloud& a, const WindowCloud& b) {
  const size_t m = a.u.size();
  const float* __restrict au = a.u.data();
  const float* __restrict av = a.v.data();
  const float* __restrict ay = a.y.data();
  const float* __restrict bu = b.u.data();
  const float* __restrict bv = b.v.data();
  const float* __restrict by = b.y.data();
  float s = 0, c = 0, dy = 0;
  for (size_t i = 0; i < m; ++i) {
    s += au[i] * bu[i] + av[i] * bv[i];
    c += av[i] * bu[i] - au[i] * bv[i];
    const float d = ay[i] - by[i];
    dy += d * d;
  }
  return std::max(0.0f, a.self_xz + b.self_xz - 2.0f * std::sqrt(s * s + c * c) + dy);
}

struct Candidate {
  float distance;
  int clip_a, frame_a, clip_b, frame_b;
};

// A cut at `frame` is allowed if it coincides with an existing cut or keeps min_gap from all.
bool cut_fits(const std::set<int>& cuts, int frame, int min_gap) {
  if (cuts.count(frame)) return true;
  auto it = cuts.lower_bound(frame);
  if (it != cuts.end() && *it - frame < min_gap) return false;
  if (it != cuts.begin() && frame - *std::prev(it) < min_gap) return false;
  return true;
}

// Clip joins: a take's end continuing into a take's start. Kovar's windows look after the cut,
// so a clip's last frames never leave it; takes cut into cycles or single moves (walk_l then
// walk_r, a crouch-walk step after step) are joined where A's last pose, carried on at its last
// velocity, matches B's first two frames under the ground alignment, with the same threshold.
void add_clip_joins(const Skeleton& skeleton, std::span<const Clip> clips, const std::vector<int>& joints,
                    const AutoGraphOptions& o, const std::vector<std::vector<int>>& segment_ending_at,
                    const std::vector<std::vector<int>>& segment_starting_at, MotionGraph& g,
                    AutoGraphReport& rep) {
  std::vector<WindowCloud> ends(clips.size()), starts(clips.size());
  std::vector<vec3> pos;
  const int n = skeleton.num_joints();
  for (size_t c = 0; c < clips.size(); ++c) {
    if (clips[c].num_frames < 2) continue;
    fk_clip_positions(skeleton, clips[c], pos);
    const int last = clips[c].num_frames - 1;
    WindowCloud e, b;
    for (int k = 0; k < 2; ++k)
      for (int j : joints) {
        const vec3 end = pos[static_cast<size_t>(last) * n + j];
        const vec3 before = pos[static_cast<size_t>(last - 1) * n + j];
        const vec3 p = k == 0 ? end : end + (end - before);  // the next frame, had it gone on
        e.u.push_back(p.x), e.v.push_back(p.z), e.y.push_back(p.y);
        const vec3 q = pos[static_cast<size_t>(k) * n + j];
        b.u.push_back(q.x), b.v.push_back(q.z), b.y.push_back(q.y);
      }
    centre(e);
    centre(b);
    ends[c] = std::move(e);
    starts[c] = std::move(b);
  }
  const float threshold = o.threshold_rms_m * o.threshold_rms_m * static_cast<float>(2 * joints.size());
  for (size_t a = 0; a < clips.size(); ++a)
    for (size_t b = 0; b < clips.size(); ++b) {
      if (ends[a].u.empty() || starts[b].u.empty()) continue;
      const int from = segment_ending_at[a][static_cast<size_t>(clips[a].num_frames - 1)];
      const int to = segment_starting_at[b][0];
      if (from < 0 || to < 0 || aligned_distance(ends[a], starts[b]) > threshold) continue;
      g.transitions.push_back({from, to, kClipJoinBlendFrames});
      ++rep.clip_joins;
    }
}

}  // namespace

bool graph_build_automatic(const Skeleton& skeleton, std::span<const Clip> clips,
                           const AutoGraphOptions& o, MotionGraph& out, AutoGraphReport* report,
                           std::string& error) {
  AutoGraphReport rep;
  if (clips.empty()) return error = "automatic graph: no clips", false;
  if (o.window_frames < 2 || o.candidate_stride < 1 || o.window_stride < 1)
    return error = "automatic graph: window_frames >= 2, strides >= 1 required", false;
  for (const Clip& c : clips)
    if (c.fps != clips[0].fps)
      return error = "automatic graph: clip '" + c.name + "' has " + std::to_string(c.fps) +
                     " fps, '" + clips[0].name + "' has " + std::to_string(clips[0].fps),
             false;

  std::vector<int> joints;
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    if (skeleton.is_end_site[j]) continue;
    bool wanted = o.joint_filter.empty();
    for (const std::string& f : o.joint_filter) wanted |= skeleton.joint_names[j].find(f) != std::string::npos;
    if (wanted) joints.push_back(j);
  }
  if (joints.empty()) return error = "automatic graph: joint filter matches no joint", false;

  std::vector<ClipFrames> clouds;
  for (const Clip& c : clips) clouds.push_back(clouds_of(skeleton, c, joints, o));
  const float points = static_cast<float>(clouds[0].num_windows ? clouds[0].windows[0].u.size() : 1);
  const float threshold = o.threshold_rms_m * o.threshold_rms_m * points;

  // Distance matrix per clip pair, then its local minima below the threshold.
  std::vector<Candidate> candidates;
  std::vector<float> d;
  for (size_t a = 0; a < clips.size(); ++a) {
    for (size_t b = 0; b < clips.size(); ++b) {
      const int na = clouds[a].num_windows, nb = clouds[b].num_windows;
      if (na == 0 || nb == 0) continue;
      d.assign(static_cast<size_t>(na) * nb, 0.0f);
      for (int i = 0; i < na; ++i)
        for (int j = 0; j < nb; ++j)
          d[static_cast<size_t>(i) * nb + j] = aligned_distance(clouds[a].windows[i], clouds[b].windows[j]);
      rep.frame_pairs_compared += static_cast<long long>(na) * nb;
      for (int i = 0; i < na; ++i) {
        for (int j = 0; j < nb; ++j) {
          const float v = d[static_cast<size_t>(i) * nb + j];
          if (v > threshold) continue;
          const int fa = i * o.candidate_stride, fb = j * o.candidate_stride;
          // Jumping within a clip to nearly the same frame is not a transition, it is playback.
          if (a == b && std::abs(fa - fb) < o.min_segment_frames) continue;
          bool minimum = true;
          for (int di = -1; di <= 1 && minimum; ++di)
            for (int dj = -1; dj <= 1 && minimum; ++dj) {
              const int ii = i + di, jj = j + dj;
              if ((di || dj) && ii >= 0 && jj >= 0 && ii < na && jj < nb)
                minimum = v <= d[static_cast<size_t>(ii) * nb + jj];
            }
          if (minimum) candidates.push_back({v, static_cast<int>(a), fa, static_cast<int>(b), fb});
        }
      }
    }
  }
  rep.local_minima = static_cast<int>(candidates.size());

  // Best transitions first; each adds a cut in A (where we leave) and in B (where we enter).
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) {
    return std::tie(x.distance, x.clip_a, x.frame_a, x.clip_b, x.frame_b) <
           std::tie(y.distance, y.clip_a, y.frame_a, y.clip_b, y.frame_b);
  });
  std::vector<std::set<int>> cuts(clips.size());
  for (size_t c = 0; c < clips.size(); ++c) cuts[c] = {0, clips[c].num_frames - 1};
  std::vector<Candidate> accepted;
  for (const Candidate& t : candidates) {
    if (!cut_fits(cuts[t.clip_a], t.frame_a, o.min_segment_frames) ||
        !cut_fits(cuts[t.clip_b], t.frame_b, o.min_segment_frames))
      continue;
    // Leaving A at its very first frame would make an empty segment.
    if (t.frame_a == 0) continue;
    cuts[t.clip_a].insert(t.frame_a);
    cuts[t.clip_b].insert(t.frame_b);
    accepted.push_back(t);
  }
  rep.transitions_accepted = static_cast<int>(accepted.size());

  // Segments between consecutive cuts, linked in clip order.
  MotionGraph g;
  std::vector<std::vector<int>> segment_starting_at(clips.size());  // per clip, per frame: segment
  std::vector<std::vector<int>> segment_ending_at(clips.size());
  for (size_t c = 0; c < clips.size(); ++c) {
    segment_starting_at[c].assign(static_cast<size_t>(clips[c].num_frames), -1);
    segment_ending_at[c].assign(static_cast<size_t>(clips[c].num_frames), -1);
    const std::vector<int> sorted(cuts[c].begin(), cuts[c].end());
    for (size_t k = 0; k + 1 < sorted.size(); ++k) {
      const int id = g.num_segments();
      g.segments.push_back({clips[c].name + "@" + std::to_string(sorted[k]), static_cast<int>(c),
                            sorted[k], sorted[k + 1], kTagLocomotion});
      segment_starting_at[c][static_cast<size_t>(sorted[k])] = id;
      segment_ending_at[c][static_cast<size_t>(sorted[k + 1])] = id;
      if (k > 0) g.transitions.push_back({id - 1, id, 0});
    }
  }
  for (const Candidate& t : accepted) {
    const int from = segment_ending_at[t.clip_a][static_cast<size_t>(t.frame_a)];
    const int to = segment_starting_at[t.clip_b][static_cast<size_t>(t.frame_b)];
    if (from >= 0 && to >= 0) g.transitions.push_back({from, to, o.window_frames});
  }
  add_clip_joins(skeleton, clips, joints, o, segment_ending_at, segment_starting_at, g, rep);
  g.finalize();
  rep.segments_before_prune = g.num_segments();
  rep.edges_before_prune = static_cast<int>(g.transitions.size());

  out = o.prune_to_largest_component ? graph_keep_segments(g, largest_strongly_connected_component(g)) : g;
  rep.segments = out.num_segments();
  rep.edges = static_cast<int>(out.transitions.size());
  if (report) *report = rep;
  if (!o.prune_to_largest_component) return true;
  if (rep.segments < 2 || rep.edges < 2)
    return error = "automatic graph: largest strongly connected component has " +
                   std::to_string(rep.segments) + " segments; raise threshold_rms_m (now " +
                   std::to_string(o.threshold_rms_m) + " m)",
           false;
  return true;
}

}  // namespace foresight

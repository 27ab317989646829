#include "terrain/upper_body_planner.hpp"

#include "math/splitmix64.hpp"

#include <algorithm>
#include <cmath>

namespace foresight::terrain {

namespace {

/// How far back from a blocked run the latest start of a manoeuvre is looked for (3 s at 30 Hz).
constexpr int kMaxManoeuvreFrames = 90;

// The common variants each part's roadmap starts with, as offsets from its pattern (paper 5.2:
// "initialized with some common motion patterns for that portion of the body").
constexpr PartConfig kWaistVariants[] = {
    {0, 0, 0, 0},       {0.35f, 0, 0, 0},     {0.70f, 0, 0, 0},      {1.05f, 0, 0, 0},
    {1.40f, 0, 0, 0},   {0, 0.40f, 0, 0},     {0, -0.40f, 0, 0},     {0, 0.80f, 0, 0},
    {0, -0.80f, 0, 0},  {0.50f, 0.50f, 0, 0}, {0.50f, -0.50f, 0, 0}, {-0.30f, 0, 0, 0},
};
constexpr PartConfig kArmVariants[] = {
    {0, 0, 0, 0},             {0.80f, 0, 0, 0},    {1.60f, 0, 0, 0},          {2.40f, 0, 0, 0},
    {-0.60f, 0, 0, 0},        {0, 0.60f, 0, 0},    {0, 1.20f, 0, 0},          {0, 0, 0, 1.20f},
    {0.80f, 0, 0, 1.20f},     {0, 1.20f, 0, 1.00f}, {1.60f, 0.40f, 0, 1.50f}, {0.40f, 0, 0.8f, 1.80f},
};

float distance(const PartConfig& a, const PartConfig& b, int dof) {
  float s = 0.0f;
  for (int i = 0; i < dof; ++i) s += (a[i] - b[i]) * (a[i] - b[i]);
  return std::sqrt(s);
}

bool finite(const PartConfig& q) {
  return std::isfinite(q[0]) && std::isfinite(q[1]) && std::isfinite(q[2]) && std::isfinite(q[3]);
}

/// Moves from `from` towards `to` at most `step` per DOF (the joint speed over one frame).
PartConfig steer(const PartConfig& from, const PartConfig& to, float step, int dof) {
  PartConfig out{};
  for (int i = 0; i < dof; ++i) out[i] = from[i] + std::clamp(to[i] - from[i], -step, step);
  return out;
}

/// One part's search. `waist` is the planned waist (arms only).
class PartSearch {
 public:
  PartSearch(UpperBodyPlanner& planner, BodyPart part, std::span<const PelvisFrame> track, float dt_s,
             const UpperBodyObstacles& obstacles, std::span<const UpperBodyConfig> waist,
             std::span<const UpperBodyConfig> guide)
      : planner_(planner), cfg_(planner.config), body_(planner.config.body), part_(part),
        dof_(part_dof(part)), track_(track), obstacles_(obstacles), waist_(waist), guide_(guide),
        step_((part == BodyPart::kWaist ? body_.waist_speed_radps : body_.arm_speed_radps) * dt_s) {}

  UpperBodyPartStats run(const PartConfig& start, std::span<UpperBodyConfig> out) {
    UpperBodyPartStats stats;
    ++planner_.stamp;
    planner_.rng.state = cfg_.seed * 0x2545F4914F6CDD1Dull + static_cast<std::uint64_t>(part_) + 1;
    seed_roadmap();
    const int last = static_cast<int>(track_.size()) - 1;
    PartConfig q0 = clamp_to_limits(body_, part_, start);
    ++stats.checks;
    if (!clear(q0, 0)) {
      stats.status = UpperBodyStatus::kStartInCollision;
      stats.frames_reached = 0;
      return stats;
    }
    mark_visited(q0, 0);
    find_blocked_frames(stats);
    int depth = 0;
    planner_.stack[0] = {q0, 0};
    stats.frames_reached = 1;
    while (depth < last) {
      if (stats.checks >= cfg_.max_checks_per_part) {
        stats.status = UpperBodyStatus::kBudget;
        return stats;
      }
      UpperBodyPlanner::Node& node = planner_.stack[static_cast<size_t>(depth)];
      PartConfig next{};
      if (try_successors(node.q, depth + 1, next, stats) || try_growing(node, depth + 1, next, stats)) {
        ++depth;
        planner_.stack[static_cast<size_t>(depth)] = {next, 0};
        stats.frames_reached = std::max(stats.frames_reached, depth + 1);
        continue;
      }
      if (stats.checks >= cfg_.max_checks_per_part) continue;  // reported as kBudget above
      if (depth == 0) {
        stats.status = UpperBodyStatus::kNoPath;
        return stats;
      }
      --depth;  // backtrack: the previous frame tries its next successor
      ++stats.backtracks;
    }
    stats.status = UpperBodyStatus::kOk;
    double deviation = 0.0;
    for (int t = 0; t <= last; ++t) {
      const PartConfig& q = planner_.stack[static_cast<size_t>(t)].q;
      out[static_cast<size_t>(t)].part(part_) = q;
      const float d = distance(q, pattern(t), dof_);
      deviation += d;
      stats.max_deviation_rad = std::max(stats.max_deviation_rad, d);
    }
    stats.mean_deviation_rad = static_cast<float>(deviation / (last + 1));
    return stats;
  }

 private:
  PartConfig pattern(int t) const { return upper_body_pattern(body_, part_, track_[static_cast<size_t>(t)]); }

  // Foresight for the search: the first frame at or after each t where the pattern itself is
  // blocked. Approaching one, the successors whose roadmap configuration is clear there come
  // first, once reaching it needs the time left (without this the search walks into the
  // obstacle erect and backtracks one frame at a time).
  void find_blocked_frames(UpperBodyPartStats& stats) {
    int next = -1, run_end = -1;
    for (int t = static_cast<int>(track_.size()) - 1; t >= 0; --t) {
      ++stats.checks;
      if (clear(pattern(t), t)) {
        run_end = -1;
      } else {
        if (run_end < 0) run_end = t;
        next = t;
        blocked_run_end_[static_cast<size_t>(t)] = run_end;
      }
      next_blocked_[static_cast<size_t>(t)] = next;
    }
    // Inside a run, the run's first frame: one run, one decision about leaving the pattern.
    for (size_t t = 1; t < track_.size(); ++t)
      if (next_blocked_[t] == static_cast<int>(t) && next_blocked_[t - 1] >= 0 &&
          next_blocked_[t - 1] < static_cast<int>(t))  // both blocked (t - 1 already holds its run's start)
        next_blocked_[t] = next_blocked_[t - 1];
    promising_tb_.fill(-1);
    latest_tb_ = latest_entry_ = -1;
  }

  /// Which roadmap entries are clear through the blocked run starting at frame tb (sampled every
  /// few frames; each entry evaluated once per tb, grown entries as they come), and for the
  /// nearest of them to the pattern the latest frame at which leaving the pattern for it, at full
  /// joint speed, still gets there clear (latest_start_). False when no entry is clear.
  bool update_promising(int tb, UpperBodyPartStats& stats) {
    const int end = blocked_run_end_[static_cast<size_t>(tb)];
    int best = -1;
    float best_size = 0.0f;
    for (int i = 0; i < planner_.roadmap_size; ++i) {
      const PartConfig& delta = planner_.roadmap[static_cast<size_t>(i)];
      if (promising_tb_[static_cast<size_t>(i)] != tb) {
        bool ok = true;
        for (int f = tb; ok && f <= end; f = (f == end ? end + 1 : std::min(f + 3, end))) {
          ++stats.checks;
          ok = clear(offset_config(f, delta), f);
        }
        promising_[static_cast<size_t>(i)] = ok;
        promising_tb_[static_cast<size_t>(i)] = tb;
      }
      const float size = distance(delta, PartConfig{}, dof_);
      if (promising_[static_cast<size_t>(i)] && (best < 0 || size < best_size)) {
        best = i;
        best_size = size;
      }
    }
    if (best < 0) return false;
    if (latest_tb_ != tb || latest_entry_ != best) {
      latest_tb_ = tb;
      latest_entry_ = best;
      latest_start_ = 0;
      // Search back from tb for the latest start whose straight manoeuvre is clear throughout
      // (configurations on the way can be blocked before tb: a half-bent head meets a lintel's
      // face before an erect one meets its underside). A run that goes on past the window may
      // need more than this window shows (a deeper bend further on): leave the pattern now.
      const bool truncated = end == static_cast<int>(track_.size()) - 1;
      const PartConfig& delta = planner_.roadmap[static_cast<size_t>(best)];
      for (int start = truncated ? -1 : tb - 1;
           start >= std::max(0, tb - kMaxManoeuvreFrames) && stats.checks < cfg_.max_checks_per_part; --start) {
        PartConfig q = pattern(start);
        bool ok = true;
        for (int f = start + 1; ok && f <= tb; ++f) {
          q = clamp_to_limits(body_, part_, steer(q, offset_config(f, delta), step_, dof_));
          ++stats.checks;
          ok = clear(q, f);
        }
        if (ok) {
          latest_start_ = start;
          break;
        }
      }
    }
    return true;
  }

  /// The pattern at frame f moved by a roadmap offset, within the limits.
  PartConfig offset_config(int f, const PartConfig& delta) const {
    const PartConfig goal = pattern(f);
    PartConfig target{};
    for (int d = 0; d < dof_; ++d) target[d] = goal[d] + delta[d];
    return clamp_to_limits(body_, part_, target);
  }

  void seed_roadmap() {
    const std::span<const PartConfig> variants =
        part_ == BodyPart::kWaist ? std::span<const PartConfig>(kWaistVariants) : std::span<const PartConfig>(kArmVariants);
    planner_.roadmap_size = first_grown_ = static_cast<int>(variants.size());
    std::copy(variants.begin(), variants.end(), planner_.roadmap.begin());
  }

  bool clear(const PartConfig& q, int t) const {
    const PelvisFrame& f = track_[static_cast<size_t>(t)];
    BodySpheres spheres;
    if (part_ == BodyPart::kWaist)
      waist_spheres(body_, f, q, spheres);
    else
      arm_spheres(body_, f, waist_[static_cast<size_t>(t)].waist, part_, q, spheres);
    return spheres_clear(spheres, obstacles_);
  }

  // The visited set: (frame, configuration cell) in an open-addressed table with generation stamps.
  std::uint64_t key(const PartConfig& q, int t) const {
    std::uint64_t k = static_cast<std::uint64_t>(t) + 1;
    for (int i = 0; i < dof_; ++i) {
      const auto cell = static_cast<std::int64_t>(std::floor(q[i] / cfg_.visit_cell_rad));
      k = k * 0x100000001B3ull ^ static_cast<std::uint64_t>(cell + 4096);
    }
    return k;
  }
  /// Marks (q, t) visited; false when it already was.
  bool mark_visited(const PartConfig& q, int t) {
    const std::uint64_t k = key(q, t);
    const size_t mask = planner_.visited_key.size() - 1;
    SplitMix64 h{k};
    for (size_t i = h.next() & mask;; i = (i + 1) & mask) {
      if (planner_.visited_stamp[i] != planner_.stamp) {
        planner_.visited_stamp[i] = planner_.stamp;
        planner_.visited_key[i] = k;
        return true;
      }
      if (planner_.visited_key[i] == k) return false;
    }
  }

  /// The roadmap's configurations at frame t, steered to from q, nearest to the pattern first.
  bool try_successors(const PartConfig& q, int t, PartConfig& next, UpperBodyPartStats& stats) {
    const PartConfig goal = pattern(t);
    const int tb = next_blocked_[static_cast<size_t>(t)];
    // Past the latest frame to leave the pattern for the run ahead: clear entries first.
    const bool urgent = tb >= 0 && update_promising(tb, stats) && t >= latest_start_;
    // The roadmap's entries, and the previous plan at this frame: tried first, unless it is time
    // to leave the pattern (the previous window may not have seen the run ahead).
    std::array<PartConfig, kMaxRoadmapNodes + 1> candidates;
    std::array<float, kMaxRoadmapNodes + 1> dist;
    std::array<int, kMaxRoadmapNodes + 1> order;
    int n = planner_.roadmap_size;
    for (int i = 0; i < n; ++i) {
      PartConfig target{};  // the pattern (computed once above) moved by the entry's offset
      for (int d = 0; d < dof_; ++d) target[d] = goal[d] + planner_.roadmap[static_cast<size_t>(i)][d];
      candidates[static_cast<size_t>(i)] = clamp_to_limits(body_, part_, steer(q, target, step_, dof_));
      dist[static_cast<size_t>(i)] = distance(candidates[static_cast<size_t>(i)], goal, dof_) +
                                     (urgent && !promising_[static_cast<size_t>(i)] ? 1e6f : 0.0f);
      order[static_cast<size_t>(i)] = i;
    }
    if (t < static_cast<int>(guide_.size())) {
      candidates[static_cast<size_t>(n)] =
          clamp_to_limits(body_, part_, steer(q, guide_[static_cast<size_t>(t)].part(part_), step_, dof_));
      dist[static_cast<size_t>(n)] = urgent ? 1e6f : -1.0f;
      order[static_cast<size_t>(n)] = n;
      ++n;
    }
    for (int i = 1; i < n; ++i)  // insertion sort: stable, few entries, and std::stable_sort allocates
      for (int j = i; j > 0 && dist[static_cast<size_t>(order[static_cast<size_t>(j)])] <
                                   dist[static_cast<size_t>(order[static_cast<size_t>(j - 1)])];
           --j)
        std::swap(order[static_cast<size_t>(j)], order[static_cast<size_t>(j - 1)]);
    for (int k = 0; k < n; ++k) {
      const PartConfig& c = candidates[static_cast<size_t>(order[static_cast<size_t>(k)])];
      if (!mark_visited(c, t)) continue;
      ++stats.checks;
      if (clear(c, t)) {
        next = c;
        return true;
      }
      if (stats.checks >= cfg_.max_checks_per_part) return false;
    }
    return false;
  }

  /// Grows new roadmap nodes r away from the stuck node (paper Fig. 5) and tries each.
  bool try_growing(UpperBodyPlanner::Node& node, int t, PartConfig& next, UpperBodyPartStats& stats) {
    while (node.grown < cfg_.grow_tries && stats.checks < cfg_.max_checks_per_part) {
      ++node.grown;
      PartConfig dir{};
      float len = 0.0f;
      for (int d = 0; d < dof_; ++d) {
        dir[d] = planner_.rng.uniform(-1.0f, 1.0f);
        len += dir[d] * dir[d];
      }
      len = std::sqrt(len);
      if (len < 1e-3f) continue;
      PartConfig grown{};
      for (int d = 0; d < dof_; ++d) grown[d] = node.q[d] + dir[d] * (cfg_.grow_distance_rad / len);
      grown = clamp_to_limits(body_, part_, grown);
      ++stats.grown;
      // The new node joins the roadmap as an offset from the pattern (the oldest grown one gives
      // way when full), so later frames can steer to it too.
      const PartConfig goal = pattern(t);
      PartConfig offset{};
      for (int d = 0; d < dof_; ++d) offset[d] = grown[d] - goal[d];
      const int slot = planner_.roadmap_size < kMaxRoadmapNodes
                           ? planner_.roadmap_size++
                           : first_grown_ + stats.grown % (kMaxRoadmapNodes - first_grown_);
      planner_.roadmap[static_cast<size_t>(slot)] = offset;
      promising_tb_[static_cast<size_t>(slot)] = -1;
      const PartConfig c = clamp_to_limits(body_, part_, steer(node.q, grown, step_, dof_));
      if (!mark_visited(c, t)) continue;
      ++stats.checks;
      if (clear(c, t)) {
        next = c;
        return true;
      }
    }
    return false;
  }

  UpperBodyPlanner& planner_;
  const UpperBodyPlannerConfig& cfg_;
  const UpperBodyParams& body_;
  BodyPart part_;
  int dof_;
  std::span<const PelvisFrame> track_;
  const UpperBodyObstacles& obstacles_;
  std::span<const UpperBodyConfig> waist_;
  std::span<const UpperBodyConfig> guide_;
  float step_;
  int first_grown_ = 0;  ///< Roadmap slots before this hold the seeded variants.
  std::array<int, kMaxUpperBodyFrames> next_blocked_{}, blocked_run_end_{};
  std::array<bool, kMaxRoadmapNodes> promising_{};
  std::array<int, kMaxRoadmapNodes> promising_tb_{};  ///< The tb each entry was evaluated for.
  int latest_tb_ = -1, latest_entry_ = -1, latest_start_ = 0;
};

static_assert(std::size(kWaistVariants) < kMaxRoadmapNodes && std::size(kArmVariants) < kMaxRoadmapNodes,
              "room for grown nodes");

}  // namespace

const char* upper_body_status_name(UpperBodyStatus status) {
  switch (status) {
    case UpperBodyStatus::kOk: return "ok";
    case UpperBodyStatus::kInvalidConfig: return "invalid config";
    case UpperBodyStatus::kBadInput: return "bad input";
    case UpperBodyStatus::kTooManyObstacles: return "too many obstacles";
    case UpperBodyStatus::kStartInCollision: return "start in collision";
    case UpperBodyStatus::kNoPath: return "no path";
    case UpperBodyStatus::kBudget: return "budget";
  }
  return "?";
}

bool upper_body_planner_init(UpperBodyPlanner& planner, const UpperBodyPlannerConfig& config) {
  planner.valid = false;
  planner.config = config;
  const UpperBodyParams& b = config.body;
  const bool ok = config.max_checks_per_part > 0 && config.max_checks_per_part <= 10'000'000 &&
                  config.grow_tries >= 0 && config.grow_distance_rad > 0.0f && config.visit_cell_rad > 0.0f &&
                  std::isfinite(config.grow_distance_rad) && std::isfinite(config.visit_cell_rad) &&
                  b.waist_speed_radps > 0.0f && b.arm_speed_radps > 0.0f && std::isfinite(b.waist_speed_radps) &&
                  std::isfinite(b.arm_speed_radps) && finite(b.waist_min) && finite(b.waist_max) &&
                  finite(b.arm_min) && finite(b.arm_max) && upper_body_params_valid(b);
  if (!ok) return false;
  // At most one visited entry per check: keep the table under half full.
  size_t size = 1024;
  while (size < 2 * static_cast<size_t>(config.max_checks_per_part) + 2 * kMaxUpperBodyFrames) size *= 2;
  planner.visited_key.assign(size, 0);
  planner.visited_stamp.assign(size, 0);
  planner.stamp = 0;
  planner.valid = true;
  return true;
}

UpperBodyConfig upper_body_pattern_config(const UpperBodyParams& params, const PelvisFrame& frame) {
  UpperBodyConfig c;
  c.waist = upper_body_pattern(params, BodyPart::kWaist, frame);
  c.arms[0] = upper_body_pattern(params, BodyPart::kLeftArm, frame);
  c.arms[1] = upper_body_pattern(params, BodyPart::kRightArm, frame);
  return c;
}

UpperBodyStatus upper_body_plan(UpperBodyPlanner& planner, std::span<const PelvisFrame> track, float dt_s,
                                const UpperBodyObstacles& obstacles, const UpperBodyConfig& start,
                                UpperBodyPlan& plan, std::span<const UpperBodyConfig> guide) {
  plan.num_frames = 0;
  plan.failed_part = BodyPart::kWaist;
  plan.parts = {};
  auto fail = [&plan](UpperBodyStatus s) { return plan.status = s; };
  if (!planner.valid) return fail(UpperBodyStatus::kInvalidConfig);
  bool ok = !track.empty() && track.size() <= kMaxUpperBodyFrames && dt_s > 0.0f && std::isfinite(dt_s) &&
            finite(start.waist) && finite(start.arms[0]) && finite(start.arms[1]);
  for (const PelvisFrame& f : track)
    ok = ok && std::isfinite(f.pos_m.x) && std::isfinite(f.pos_m.y) && std::isfinite(f.pos_m.z) &&
         std::isfinite(f.heading_rad) && std::isfinite(f.left_hip_rad) && std::isfinite(f.right_hip_rad);
  if (!ok) return fail(UpperBodyStatus::kBadInput);
  if (obstacles.overflow) return fail(UpperBodyStatus::kTooManyObstacles);
  const std::span<UpperBodyConfig> frames(plan.frames.data(), track.size());
  for (BodyPart part : {BodyPart::kWaist, BodyPart::kLeftArm, BodyPart::kRightArm}) {
    PartSearch search(planner, part, track, dt_s, obstacles, frames, guide.first(std::min(guide.size(), track.size())));
    UpperBodyPartStats& stats = plan.parts[static_cast<size_t>(part)];
    stats = search.run(start.part(part), frames);
    if (stats.status != UpperBodyStatus::kOk) {
      plan.failed_part = part;
      return fail(stats.status);
    }
  }
  plan.num_frames = static_cast<int>(track.size());
  return plan.status = UpperBodyStatus::kOk;
}

int pelvis_track_from_plan(const FootstepPlan& plan, const WalkParams& walk, const GroundPath& path,
                           float speed_mps, float dt_s, bool first_swing_left, std::span<PelvisFrame> out,
                           int& first_step_frames) {
  first_step_frames = 0;
  if (plan.num_steps <= 0 || out.empty() || !(speed_mps > 0.0f) || !(dt_s > 0.0f)) return 0;
  int written = 0;
  WalkFrame w;
  auto emit = [&](const WalkStep& step, float phase, bool swing_left) {
    walk_step_sample(step, walk, phase, w);
    PelvisFrame& f = out[static_cast<size_t>(written++)];
    const vec2 g = ground_path_point(path, w.pelvis_m.x);
    f.pos_m = vec3(g.x, w.pelvis_m.y, g.y);
    f.heading_rad = ground_path_heading(path, w.pelvis_m.x);
    f.left_hip_rad = swing_left ? w.swing.hip_rad : w.stance.hip_rad;
    f.right_hip_rad = swing_left ? w.stance.hip_rad : w.swing.hip_rad;
  };
  emit(plan.steps[0], 0.0f, first_swing_left);
  for (int i = 0; i < plan.num_steps && written < static_cast<int>(out.size()); ++i) {
    const WalkStep& step = plan.steps[static_cast<size_t>(i)];
    const bool swing_left = first_swing_left == (i % 2 == 0);
    const float advance_m = step.keys[2].pelvis_m.x - step.keys[0].pelvis_m.x;
    const int frames = std::max(1, static_cast<int>(std::lround(advance_m / speed_mps / dt_s)));
    for (int j = 1; j <= frames && written < static_cast<int>(out.size()); ++j)
      emit(step, static_cast<float>(j) / static_cast<float>(frames), swing_left);
    if (i == 0) first_step_frames = written - 1;
  }
  return written;
}

}  // namespace foresight::terrain

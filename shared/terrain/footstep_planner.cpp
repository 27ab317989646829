#include "terrain/footstep_planner.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace foresight::terrain {

namespace {

// One plan's search state: the window's fixed feet, the current configuration's cumulative grid
// offsets K_i = k_1 + ... + k_i (step i lands at stance + i * s_min + K_i * delta).
struct Search {
  FootstepPlanner& planner;
  const GroundProfile& profile;
  Foothold rear, stance;
  int n, m;
};

float position(const Search& s, int i, int cumulative) {
  return s.stance.x_m + static_cast<float>(i) * s.planner.config.step_min_m +
         static_cast<float>(cumulative) * s.planner.step_delta_m;
}

void count_failure(FootstepPlanner& planner, WalkStatus status) {
  const auto k = static_cast<std::size_t>(status);
  if (k < planner.failure_counts.size()) ++planner.failure_counts[k];
}

// Foothold of step i (1..n+1) at cumulative offset K, memoised for this plan.
const FootstepPlanner::FootholdEntry& foothold_at(Search& s, int i, int cumulative, FootstepPlan& plan) {
  FootstepPlanner& p = s.planner;
  const int stride = (s.n + 1) * s.m + 1;
  FootstepPlanner::FootholdEntry& e =
      p.footholds[static_cast<std::size_t>((i - 1) * stride + cumulative)];
  if (e.stamp != p.stamp) {
    e.stamp = p.stamp;
    e.status = foothold_fit(s.profile, p.config.walk, position(s, i, cumulative), e.foothold);
    ++plan.foothold_checks;
  }
  return e;
}

// Step i (1..n) of the configuration whose cumulative offsets are `cum` (cum[0] = 0 = stance).
// Memoised by (i, K_{i-1}, k_{i-1}, k_i): that fixes the rear, stance and landing positions.
const FootstepPlanner::StepEntry& step_at(Search& s, int i, const int* cum, FootstepPlan& plan) {
  FootstepPlanner& p = s.planner;
  const int k_prev = i >= 2 ? cum[i - 1] - cum[i - 2] : 0;
  const int k = cum[i] - cum[i - 1];
  const std::size_t index =
      ((static_cast<std::size_t>(i - 1) * static_cast<std::size_t>(s.n * s.m + 1) +
        static_cast<std::size_t>(cum[i - 1])) * static_cast<std::size_t>(s.m + 1) +
       static_cast<std::size_t>(k_prev)) * static_cast<std::size_t>(s.m + 1) +
      static_cast<std::size_t>(k);
  FootstepPlanner::StepEntry& e = p.step_memo[index];
  if (e.stamp == p.stamp) return e;
  e.stamp = p.stamp;
  e.cost = 0.0f;
  const FootstepPlanner::FootholdEntry& land = foothold_at(s, i, cum[i], plan);
  if (land.status != WalkStatus::kOk) {
    e.status = land.status;
    count_failure(p, e.status);
    return e;
  }
  const Foothold& stance = i == 1 ? s.stance : foothold_at(s, i - 1, cum[i - 1], plan).foothold;
  const Foothold& rear = i == 1   ? s.rear
                         : i == 2 ? s.stance
                                  : foothold_at(s, i - 2, cum[i - 2], plan).foothold;
  WalkStep step;
  e.status = walk_step_plan(s.profile, p.config.walk, rear, stance, land.foothold, step);
  ++plan.step_checks;
  if (e.status != WalkStatus::kOk) {
    count_failure(p, e.status);
    return e;
  }
  const FootstepPlannerConfig& c = p.config;
  const float length = position(s, i, cum[i]) - position(s, i - 1, cum[i - 1]);
  const float dev = (length - c.step_neutral_m) / c.step_neutral_m;
  const float dh = land.foothold.sole_y_m - stance.sole_y_m;
  e.cost = c.w_length * dev * dev + c.w_up * std::max(dh, 0.0f) + c.w_down * std::max(-dh, 0.0f) +
           c.w_lift * step.lift_m + c.w_pitch * std::abs(land.foothold.pitch_rad);
  return e;
}

// Beyond the paper: the window's last foothold must leave a next foothold within one step and
// within the height limits, or the next window would start in a dead end.
bool viable_at(Search& s, int cum_n, FootstepPlan& plan) {
  FootstepPlanner& p = s.planner;
  std::uint32_t& e = p.viable[static_cast<std::size_t>(cum_n)];
  if ((e >> 1) == p.stamp) return (e & 1u) != 0;
  const Foothold last = foothold_at(s, s.n, cum_n, plan).foothold;
  bool ok = false;
  for (int k = 0; k <= s.m && !ok; ++k) {
    const FootstepPlanner::FootholdEntry& next = foothold_at(s, s.n + 1, cum_n + k, plan);
    WalkStatus why = next.status;
    if (why == WalkStatus::kOk) {
      const float dh = next.foothold.sole_y_m - last.sole_y_m;
      why = dh > p.config.walk.max_step_up_m     ? WalkStatus::kStepTooHigh
            : dh < -p.config.walk.max_step_down_m ? WalkStatus::kStepTooLow
                                                  : WalkStatus::kOk;
    }
    if (why == WalkStatus::kOk) ok = true;
    else count_failure(p, why);
  }
  e = (p.stamp << 1) | (ok ? 1u : 0u);
  return ok;
}

// Feasibility and cost of a configuration (grid indices k_1..k_n). Returns 0 when feasible, else
// the 1-based index of the first failing step (n when only the viability test fails): step i
// depends on k_1..k_i alone, so no change to a later step can repair it.
int evaluate(Search& s, const int* k, float& cost, FootstepPlan& plan) {
  int cum[kMaxWindowSteps + 1];
  cum[0] = 0;
  for (int i = 1; i <= s.n; ++i) cum[i] = cum[i - 1] + k[i - 1];
  ++plan.configs_evaluated;
  cost = 0.0f;
  for (int i = 1; i <= s.n; ++i) {
    const FootstepPlanner::StepEntry& e = step_at(s, i, cum, plan);
    if (e.status != WalkStatus::kOk) return i;
    cost += e.cost;
  }
  if (s.planner.config.require_next_foothold && !viable_at(s, cum[s.n], plan)) return s.n;
  return 0;
}

std::uint32_t encode(const int* k, int n, int m) {
  std::uint32_t code = 0;
  for (int i = n - 1; i >= 0; --i) code = code * static_cast<std::uint32_t>(m + 1) + static_cast<std::uint32_t>(k[i]);
  return code;
}

void decode(std::uint32_t code, int n, int m, int* k) {
  for (int i = 0; i < n; ++i) {
    k[i] = static_cast<int>(code % static_cast<std::uint32_t>(m + 1));
    code /= static_cast<std::uint32_t>(m + 1);
  }
}

FootstepStatus status_from(WalkStatus w) {
  switch (w) {
    case WalkStatus::kStepTooHigh: return FootstepStatus::kWall;
    case WalkStatus::kStepTooLow: return FootstepStatus::kCliff;
    case WalkStatus::kFootInGap: return FootstepStatus::kGap;
    case WalkStatus::kNoClearance: return FootstepStatus::kObstacle;
    case WalkStatus::kFootholdUneven: return FootstepStatus::kUnevenGround;
    case WalkStatus::kUnreachable: return FootstepStatus::kUnreachable;
    case WalkStatus::kOutsideProfile:
    case WalkStatus::kOk: break;
  }
  return FootstepStatus::kEndOfProfile;
}

// The most frequent fresh failure of this plan; ties go to the lower enum (deterministic).
FootstepStatus dominant_failure(const FootstepPlanner& p) {
  std::size_t best = static_cast<std::size_t>(WalkStatus::kOutsideProfile);
  for (std::size_t k = 1; k < p.failure_counts.size(); ++k)
    if (p.failure_counts[k] > p.failure_counts[best]) best = k;
  return status_from(static_cast<WalkStatus>(best));
}

// Breadth-first from the seed to a nearby collision-free configuration (grid neighbours).
bool bfs(Search& s, int* k, float& cost, FootstepPlan& plan) {
  FootstepPlanner& p = s.planner;
  std::fill(p.visited.begin(), p.visited.end(), 0ull);
  std::size_t head = 0, tail = 0;
  const std::uint32_t start = encode(k, s.n, s.m);
  p.queue[tail++] = start;
  p.visited[start >> 6] |= 1ull << (start & 63);
  while (head < tail) {
    const std::uint32_t code = p.queue[head++];
    ++plan.bfs_expanded;
    decode(code, s.n, s.m, k);
    const int failing = evaluate(s, k, cost, plan);
    if (failing == 0) return true;
    // Only steps up to the failing one can repair it. Every feasible configuration stays reachable
    // (change the steps in order, first to last), so this prunes the search without losing any.
    for (int i = 0; i < failing; ++i) {
      for (int d = -1; d <= 1; d += 2) {
        const int v = k[i] + d;
        if (v < 0 || v > s.m) continue;
        k[i] = v;
        const std::uint32_t next = encode(k, s.n, s.m);
        k[i] -= d;
        if (p.visited[next >> 6] & (1ull << (next & 63))) continue;
        p.visited[next >> 6] |= 1ull << (next & 63);
        assert(tail < p.queue.size());
        p.queue[tail++] = next;
      }
    }
  }
  return false;
}

// Steepest descent over the grid neighbours; stops when every feasible neighbour is worse.
void descend(Search& s, int* k, float& cost, FootstepPlan& plan) {
  for (int guard = 0; guard < s.planner.num_configs; ++guard) {
    int best_i = -1, best_d = 0;
    float best_cost = cost;
    for (int i = 0; i < s.n; ++i) {
      for (int d = -1; d <= 1; d += 2) {
        const int v = k[i] + d;
        if (v < 0 || v > s.m) continue;
        k[i] = v;
        float c = 0.0f;
        if (evaluate(s, k, c, plan) == 0 && c < best_cost - 1e-6f) {
          best_cost = c;
          best_i = i;
          best_d = d;
        }
        k[i] -= d;
      }
    }
    if (best_i < 0) return;
    k[best_i] += best_d;
    cost = best_cost;
    ++plan.descent_moves;
  }
}

bool finite(float v) { return std::isfinite(v); }

}  // namespace

const char* footstep_status_name(FootstepStatus status) {
  switch (status) {
    case FootstepStatus::kOk: return "ok";
    case FootstepStatus::kInvalidConfig: return "invalid-config";
    case FootstepStatus::kEmptyProfile: return "empty-profile";
    case FootstepStatus::kBadStart: return "bad-start";
    case FootstepStatus::kWall: return "wall";
    case FootstepStatus::kCliff: return "cliff";
    case FootstepStatus::kGap: return "gap";
    case FootstepStatus::kObstacle: return "obstacle";
    case FootstepStatus::kUnevenGround: return "uneven-ground";
    case FootstepStatus::kUnreachable: return "unreachable";
    case FootstepStatus::kEndOfProfile: return "end-of-profile";
  }
  return "?";
}

bool footstep_planner_init(FootstepPlanner& planner, const FootstepPlannerConfig& config) {
  planner.valid = false;
  planner.config = config;
  const int n = config.window_steps, m = config.intervals;
  if (n < 1 || n > kMaxWindowSteps || m < 1 || m > kMaxStepIntervals) return false;
  if (!finite(config.step_min_m) || !finite(config.step_max_m) || !finite(config.step_neutral_m) ||
      !(config.step_min_m > 0.0f) || !(config.step_max_m > config.step_min_m))
    return false;
  planner.step_delta_m = (config.step_max_m - config.step_min_m) / static_cast<float>(m);
  const float neutral = std::clamp(config.step_neutral_m, config.step_min_m, config.step_max_m);
  planner.neutral_index =
      static_cast<int>(std::lround((neutral - config.step_min_m) / planner.step_delta_m));
  planner.config.step_neutral_m =
      config.step_min_m + static_cast<float>(planner.neutral_index) * planner.step_delta_m;
  planner.num_configs = 1;
  for (int i = 0; i < n; ++i) planner.num_configs *= m + 1;
  const auto nm = static_cast<std::size_t>(n * m + 1);
  const auto m1 = static_cast<std::size_t>(m + 1);
  planner.footholds.assign(static_cast<std::size_t>(n + 1) * static_cast<std::size_t>((n + 1) * m + 1),
                           {Foothold{}, WalkStatus::kOk, 0u});
  planner.step_memo.assign(static_cast<std::size_t>(n) * nm * m1 * m1, {0.0f, WalkStatus::kOk, 0u});
  planner.viable.assign(nm, 0u);
  planner.visited.assign((static_cast<std::size_t>(planner.num_configs) + 63) / 64, 0ull);
  planner.queue.assign(static_cast<std::size_t>(planner.num_configs), 0u);
  planner.stamp = 0;
  planner.valid = true;
  return true;
}

FootstepStatus footstep_plan(FootstepPlanner& planner, const GroundProfile& profile,
                             const FootstepWindow& window, FootstepPlan& plan) {
  plan = FootstepPlan{};
  const auto fail = [&](FootstepStatus status) {
    plan.status = status;
    plan.num_steps = 0;
    return status;
  };
  if (!planner.valid) return fail(FootstepStatus::kInvalidConfig);
  if (profile.num_samples <= 0) return fail(FootstepStatus::kEmptyProfile);
  const WalkParams& walk = planner.config.walk;
  Search s{planner, profile, {}, {}, planner.config.window_steps, planner.config.intervals};
  if (!finite(window.rear_x_m) || !finite(window.stance_x_m) ||
      foothold_fit(profile, walk, window.stance_x_m, s.stance) != WalkStatus::kOk ||
      foothold_fit(profile, walk, window.rear_x_m, s.rear) != WalkStatus::kOk)
    return fail(FootstepStatus::kBadStart);
  // A new generation invalidates every memo entry at once; on wrap-around clear them for real.
  if (++planner.stamp >= (1u << 30)) {
    footstep_planner_init(planner, planner.config);
    planner.stamp = 1;
  }
  planner.failure_counts.fill(0);

  int k[kMaxWindowSteps];
  for (int i = 0; i < s.n; ++i)
    k[i] = window.seeded ? std::clamp<int>(window.seed_index[static_cast<std::size_t>(i)], 0, s.m)
                         : planner.neutral_index;
  float cost = 0.0f;
  if (!bfs(s, k, cost, plan)) return fail(dominant_failure(planner));
  descend(s, k, cost, plan);

  // The chosen window, with each step's motion ready to sample.
  Foothold rear = s.rear, stance = s.stance;
  int cum = 0;
  for (int i = 0; i < s.n; ++i) {
    const auto si = static_cast<std::size_t>(i);
    cum += k[i];
    // The positions the search used (same grid sums), so these repeat checks that passed.
    const float pos = position(s, i + 1, cum);
    Foothold land;
    if (foothold_fit(profile, walk, pos, land) != WalkStatus::kOk ||
        walk_step_plan(profile, walk, rear, stance, land, plan.steps[si]) != WalkStatus::kOk)
      return fail(FootstepStatus::kUnreachable);  // Not expected; kept so a bug cannot emit NaN.
    plan.step_index[si] = static_cast<std::int8_t>(k[i]);
    plan.step_length_m[si] = pos - stance.x_m;
    plan.footholds[si] = land;
    rear = stance;
    stance = land;
  }
  plan.cost = cost;
  plan.num_steps = s.n;
  plan.status = FootstepStatus::kOk;
  return plan.status;
}

void footstep_window_slide(const FootstepPlanner& planner, const FootstepPlan& plan,
                           FootstepWindow& window) {
  assert(plan.status == FootstepStatus::kOk && plan.num_steps >= 1);
  window.rear_x_m = window.stance_x_m;
  window.stance_x_m = plan.footholds[0].x_m;
  const int n = plan.num_steps;
  for (int i = 0; i + 1 < n; ++i)
    window.seed_index[static_cast<std::size_t>(i)] = plan.step_index[static_cast<std::size_t>(i + 1)];
  window.seed_index[static_cast<std::size_t>(n - 1)] = static_cast<std::int8_t>(planner.neutral_index);
  window.seeded = true;
}

WalkStatus fixed_step_advance(const GroundProfile& profile, const WalkParams& params, float step_m,
                              FootstepWindow& window, WalkStep& out) {
  Foothold rear, stance, land;
  WalkStatus st = foothold_fit(profile, params, window.stance_x_m, stance);
  if (st != WalkStatus::kOk) return st;
  st = foothold_fit(profile, params, window.rear_x_m, rear);
  if (st != WalkStatus::kOk) return st;
  st = foothold_fit(profile, params, window.stance_x_m + step_m, land);
  if (st != WalkStatus::kOk) return st;
  st = walk_step_plan(profile, params, rear, stance, land, out);
  if (st != WalkStatus::kOk) return st;
  window.rear_x_m = window.stance_x_m;
  window.stance_x_m = land.x_m;
  return WalkStatus::kOk;
}

}  // namespace foresight::terrain

// Fig. 9: average tree size per strategy and frame interval, the shape checks, the turnover.
#include "lab/lab_experiments.hpp"

#include "lab/lab_driver.hpp"
#include "lab/lab_internal.hpp"

#include <algorithm>
#include <cstdio>

namespace foresight::lab {

using namespace detail;

// ---- Fig. 9 ---------------------------------------------------------------------------------

double linear_r2(const std::vector<double>& x, const std::vector<double>& y) {
  const size_t n = std::min(x.size(), y.size());
  if (n < 3) return 1.0;
  const double mx = mean(x), my = mean(y);
  double sxx = 0, sxy = 0, syy = 0;
  for (size_t i = 0; i < n; ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
    syy += (y[i] - my) * (y[i] - my);
  }
  if (syy <= 1e-12 || sxx <= 1e-12) return 1.0;
  return sxy * sxy / (sxx * syy);
}

std::vector<ShapeCheck> check_fig9_shape(const TreeSizeTable& t) {
  // Only intervals with a budget: at zero spare time every strategy keeps the bare root.
  std::vector<size_t> cols;
  for (size_t i = 0; i < t.intervals_s.size(); ++i)
    if (t.budgets[i] > 0) cols.push_back(i);
  std::array<double, kNumStrategies> avg{};
  for (int s = 0; s < kNumStrategies; ++s) {
    std::vector<double> v;
    for (size_t i : cols) v.push_back(t.avg_tree_size[static_cast<size_t>(s)][i]);
    avg[static_cast<size_t>(s)] = mean(v);
  }
  auto fmt = [](double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.1f", v);
    return std::string(b);
  };
  // How many of the intervals agree with a pairwise claim a > b.
  auto per_interval = [&](int a, int b) {
    int agree = 0;
    for (size_t i : cols)
      agree += t.avg_tree_size[static_cast<size_t>(a)][i] > t.avg_tree_size[static_cast<size_t>(b)][i];
    return std::to_string(agree) + "/" + std::to_string(cols.size()) + " intervals";
  };

  std::vector<ShapeCheck> checks;
  {
    ShapeCheck c{"tree size grows about linearly with spare time (R^2 >= 0.95, increasing)", true, ""};
    for (int s = 0; s < kNumStrategies; ++s) {
      std::vector<double> x, y;
      for (size_t i : cols) {
        x.push_back(t.model.spare_s(t.intervals_s[i]));
        y.push_back(t.avg_tree_size[static_cast<size_t>(s)][i]);
      }
      std::vector<double> per_second;  // expansions per second of clip (= display) time
      for (size_t i : cols) per_second.push_back(static_cast<double>(t.budgets[i]) / t.intervals_s[i]);
      const double r2 = linear_r2(x, y);
      const bool increasing = y.size() < 2 || y.back() > y.front();
      if (r2 < 0.95 || !increasing) c.holds = false;
      char b[96];
      std::snprintf(b, sizeof b, "%stype %d R2=%.3f%s (vs expansions/s: %.3f)", s ? "; " : "", s, r2,
                    increasing ? "" : " not increasing", linear_r2(per_second, y));
      c.detail += b;
    }
    checks.push_back(c);
  }
  {
    ShapeCheck c{"type 0 (breadth-first) has the smallest tree", true, ""};
    for (int s = 1; s < kNumStrategies; ++s)
      if (avg[0] >= avg[static_cast<size_t>(s)]) {
        c.holds = false;
        c.detail += "0 (" + fmt(avg[0]) + ") >= " + std::to_string(s) + " (" +
                    fmt(avg[static_cast<size_t>(s)]) + "); ";
      }
    if (c.holds) c.detail = "mean 0 = " + fmt(avg[0]);
    checks.push_back(c);
  }
  checks.push_back({"type 1 (re-sorted) > type 2 (not re-sorted)", avg[1] > avg[2],
                    "1 = " + fmt(avg[1]) + ", 2 = " + fmt(avg[2]) + "; 1 > 2 in " + per_interval(1, 2)});
  {
    ShapeCheck c{"type 3 (statistic) has the largest tree", true, ""};
    for (int s = 0; s < kNumStrategies; ++s)
      if (s != 3 && avg[3] <= avg[static_cast<size_t>(s)]) {
        c.holds = false;
        c.detail += "3 (" + fmt(avg[3]) + ") <= " + std::to_string(s) + " (" +
                    fmt(avg[static_cast<size_t>(s)]) + "); ";
      }
    if (c.holds) c.detail = "mean 3 = " + fmt(avg[3]);
    checks.push_back(c);
  }
  {
    const double lo = std::min(avg[1], avg[3]), hi = std::max(avg[1], avg[3]);
    checks.push_back({"type 4 (hybrid) lies between types 1 and 3", avg[4] >= lo && avg[4] <= hi,
                      "1 = " + fmt(avg[1]) + ", 4 = " + fmt(avg[4]) + ", 3 = " + fmt(avg[3])});
  }
  return checks;
}

TreeSizeTable run_tree_sizes(const LabScene& lab, const LabOptions& options,
                             const SpareTimeModel& model, const TransitionStatistics& statistics) {
  TreeSizeTable t;
  t.model = model;
  t.intervals_s = lab_intervals(options);
  for (double interval : t.intervals_s) t.budgets.push_back(model.expansions_per_frame(interval));
  for (int s = 0; s < kNumStrategies; ++s) {
    MotionTreeConfig tree = options.tree;
    tree.strategy = static_cast<Strategy>(s);
    for (size_t i = 0; i < t.intervals_s.size(); ++i) {
      ReplayConfig c = lab_replay_config(tree, t.intervals_s[i], t.budgets[i]);
      // The paper's protocol: every strategy replays the same commands over the same time span.
      c.stop_at_goal = false;
      c.max_seconds = lab.eval.duration_s();
      if (uses_statistics(tree.strategy)) c.statistics = statistics;
      const ReplayResult res = replay_recording(lab.library, lab.world, lab.eval, c);
      if (!res.error.empty() && t.error.empty()) t.error = res.error;
      t.avg_tree_size[static_cast<size_t>(s)].push_back(res.avg_tree_size);
    }
  }
  return t;
}

Fig9Result run_fig9(const LabScene& lab, const LabOptions& options,
                    const TransitionStatistics& statistics) {
  Fig9Result r;
  const SpareTimeModel paper{options.frame_cost_s, options.paper_expansions_per_s};
  r.paper = run_tree_sizes(lab, options, paper, statistics);
  r.shape = check_fig9_shape(r.paper);
  r.turnover_interval_s = options.turnover_interval_s;
  for (int s = 0; s < kNumStrategies; ++s) {
    MotionTreeConfig tree = options.tree;
    tree.strategy = static_cast<Strategy>(s);
    ReplayConfig c = lab_replay_config(tree, r.turnover_interval_s,
                                       paper.expansions_per_frame(r.turnover_interval_s));
    c.max_seconds = lab.eval.duration_s();
    if (uses_statistics(tree.strategy)) c.statistics = statistics;
    std::string error;
    r.turnover[static_cast<size_t>(s)] = drive_turnover(lab.library, lab.world, lab.eval, c, error);
    if (!error.empty() && r.error.empty()) r.error = error;
  }
  r.rate = measure_expansion_rate(lab, options);
  if (r.error.empty()) r.error = !r.paper.error.empty() ? r.paper.error : r.rate.error;
  const SpareTimeModel today{options.frame_cost_s, r.rate.expansions_per_s};
  if (options.today_rate) r.today = run_tree_sizes(lab, options, today, statistics);
  else r.today.model = today;
  if (r.error.empty()) r.error = r.today.error;
  return r;
}

}  // namespace foresight::lab

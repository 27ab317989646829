#include "lab/lab_report.hpp"

#include "bench_json.hpp"
#include "lab/svg_plot.hpp"
#include "machine_info.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

namespace foresight::lab {
namespace {

std::string fmt(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

/// "1/30" for an interval that is the inverse of a whole frame rate, else milliseconds.
std::string interval_label(double interval_s) {
  const double fps = 1.0 / interval_s;
  if (std::fabs(fps - std::round(fps)) < 1e-6) return "1/" + fmt("%.0f", fps);
  return fmt("%.1f ms", interval_s * 1000.0);
}

std::string strategy_title(int s) {
  return std::to_string(s) + " " + std::string(strategy_name(static_cast<Strategy>(s)));
}

std::string pad(const std::string& s, size_t width, bool right = true) {
  if (s.size() >= width) return s;
  return right ? std::string(width - s.size(), ' ') + s : s + std::string(width - s.size(), ' ');
}

/// "[a,b,c]" for the text tables: each element as `f` writes it.
template <typename T, typename F>
std::string bracketed(const std::vector<T>& v, F&& f) {
  std::string out = "[";
  for (size_t i = 0; i < v.size(); ++i) out += (i ? "," : "") + f(v[i]);
  return out + "]";
}

std::string tree_size_table_text(const TreeSizeTable& t, const std::string& title) {
  std::string out = title + "\n";
  out += "  interval   spare ms   budget |";
  for (int s = 0; s < kNumStrategies; ++s) out += pad(strategy_title(s), 21);
  out += "\n";
  for (size_t i = 0; i < t.intervals_s.size(); ++i) {
    out += "  " + pad(interval_label(t.intervals_s[i]), 8, false) +
           pad(fmt("%.1f", 1000.0 * t.model.spare_s(t.intervals_s[i])), 11) +
           pad(std::to_string(t.budgets[i]), 9) + " |";
    for (int s = 0; s < kNumStrategies; ++s)
      out += pad(fmt("%.1f", t.avg_tree_size[static_cast<size_t>(s)][i]), 21);
    out += "\n";
  }
  return out;
}

void add_tree_size_rows(CsvTable& csv, const TreeSizeTable& t, const std::string& model) {
  for (int s = 0; s < kNumStrategies; ++s)
    for (size_t i = 0; i < t.intervals_s.size(); ++i)
      csv.rows.push_back({model, format_number(t.model.expansions_per_s, 0), std::to_string(s),
                          std::string(strategy_name(static_cast<Strategy>(s))),
                          format_number(t.intervals_s[i], 6),
                          format_number(1.0 / t.intervals_s[i], 2),
                          format_number(t.model.spare_s(t.intervals_s[i]), 6),
                          std::to_string(t.budgets[i]),
                          format_number(t.avg_tree_size[static_cast<size_t>(s)][i], 3)});
}

bool write_text(const std::filesystem::path& path, const std::string& text, std::string& error) {
  std::ofstream out(path, std::ios::binary);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (!out) {
    error = path.string() + ": cannot write";
    return false;
  }
  return true;
}

}  // namespace

// ---- Fig. 9 ---------------------------------------------------------------------------------

std::string fig9_text(const Fig9Result& f) {
  std::string out;
  out += "Spare-time model: spare = max(0, interval - " +
         fmt("%.2f", 1000.0 * f.paper.model.frame_cost_s) +
         " ms frame cost); budget = spare x expansion rate (expansions per frame)\n";
  out += tree_size_table_text(
      f.paper, "Fig. 9: average tree size (nodes) over the eval recording, paper-like rate " +
                   fmt("%.0f", f.paper.model.expansions_per_s) + " expansions/s");
  out += "Today's rate: " + fmt("%.0f", f.rate.expansions_per_s) + " expansions/s (" +
         std::to_string(f.rate.expansions) + " expansions, " + std::to_string(f.rate.trees) +
         " trees, " + fmt("%.2f", f.rate.seconds) + " s of MotionTree::grow on one thread)\n";
  if (f.today.intervals_s.empty())
    out += "Fig. 9 at today's rate: not replayed (today_rate off)\n";
  else
    out += tree_size_table_text(
        f.today, "Fig. 9 at today's rate (trees capped by max_nodes and the depth limit)");
  out += "Paper's shape (Fig. 9, paper-like rate, intervals with a budget):\n";
  for (const ShapeCheck& c : f.shape)
    out += std::string("  [") + (c.holds ? "holds" : "FAILS") + "] " + c.claim + ": " + c.detail + "\n";
  out += "Tree turnover at " + interval_label(f.turnover_interval_s) +
         " (paper-like rate): what survives a root advance decides the average size\n";
  out += "  type                      avg size  nodes added  advances  size before advance  kept share  kept mean depth\n";
  for (int s = 0; s < kNumStrategies; ++s) {
    const TreeTurnover& t = f.turnover[static_cast<size_t>(s)];
    out += "  " + pad(strategy_title(s), 24, false) + pad(fmt("%.1f", t.avg_tree_size), 10) +
           pad(std::to_string(t.nodes_added), 13) + pad(std::to_string(t.advances), 10) +
           pad(fmt("%.0f", t.mean_size_before_advance), 21) +
           pad(fmt("%.0f%%", 100.0 * t.mean_kept_share), 12) + pad(fmt("%.2f", t.mean_kept_depth), 17) + "\n";
  }
  return out;
}

CsvTable fig9_csv(const Fig9Result& f) {
  CsvTable csv;
  csv.header = {"rate_model", "expansions_per_s", "strategy", "strategy_name", "interval_s", "fps",
                "spare_s", "expansions_per_frame", "avg_tree_size"};
  add_tree_size_rows(csv, f.paper, "paper");
  add_tree_size_rows(csv, f.today, "today");
  return csv;
}

std::string fig9_svg(const Fig9Result& f, const std::string& scene) {
  LineChart chart;
  chart.title = "Fig. 9 (" + scene + "): average feasible-motion-tree size vs frame interval";
  chart.x_label = "frame interval (s)";
  chart.y_label = "average tree size (nodes)";
  chart.notes = {"spare = max(0, interval - " + fmt("%.1f", 1000.0 * f.paper.model.frame_cost_s) +
                     " ms); budget = spare x " + fmt("%.0f", f.paper.model.expansions_per_s) +
                     " expansions/s (a 2005 PC); eval recording replayed with each strategy",
                 bench::machine_description()};
  for (int s = 0; s < kNumStrategies; ++s) {
    LineSeries series;
    series.name = "type " + strategy_title(s);
    for (size_t i = 0; i < f.paper.intervals_s.size(); ++i)
      series.points.push_back({f.paper.intervals_s[i], f.paper.avg_tree_size[static_cast<size_t>(s)][i]});
    chart.series.push_back(std::move(series));
  }
  return svg_line_chart(chart);
}

// ---- Fig. 10 --------------------------------------------------------------------------------

CsvTable fig10_csv(const Fig10Result& f) {
  CsvTable csv;
  csv.header = {"strategy", "strategy_name", "node", "depth", "end_x_m", "end_z_m"};
  for (const Fig10Panel& p : f.panels)
    for (size_t i = 0; i < p.end_positions_m.size(); ++i)
      csv.rows.push_back({std::to_string(static_cast<int>(p.strategy)),
                          std::string(strategy_name(p.strategy)), std::to_string(i),
                          std::to_string(p.depths[i]), format_number(p.end_positions_m[i].x, 3),
                          format_number(p.end_positions_m[i].y, 3)});
  return csv;
}

std::string fig10_text(const Fig10Result& f) {
  std::string out = "Fig. 10: future root positions, one common state: t = " + fmt("%.2f", f.time_s) +
                    " s of the eval recording, avatar at (" + fmt("%.2f", f.avatar.pos_m.x) + ", " +
                    fmt("%.2f", f.avatar.pos_m.y) + "), heading " +
                    fmt("%.0f", degrees(f.avatar.heading_rad)) + " deg, command towards " +
                    fmt("%.0f", degrees(heading_of(f.command_world))) + " deg;\n  each strategy grows a fresh tree for " +
                    std::to_string(f.grow_frames) + " frames x " + std::to_string(f.expansions_per_frame) +
                    " expansions (interval " + interval_label(f.interval_s) + ", paper-like rate)\n";
  for (const Fig10Panel& p : f.panels) {
    // How far ahead the tree reaches along the command, and how wide it spreads across it.
    const float cl = glm::length(f.command_world);
    const vec2 u = cl > 0.0f ? f.command_world / cl : vec2(std::sin(f.avatar.heading_rad), std::cos(f.avatar.heading_rad));
    float ahead = 0.0f, side = 0.0f;
    for (const vec2& q : p.end_positions_m) {
      const vec2 d = q - f.avatar.pos_m;
      ahead = std::max(ahead, glm::dot(d, u));
      side = std::max(side, std::fabs(u.x * d.y - u.y * d.x));
    }
    out += "  type " + pad(strategy_title(static_cast<int>(p.strategy)), 21, false) +
           pad(std::to_string(p.end_positions_m.size()), 5) + " nodes, depth " +
           std::to_string(p.max_depth) + ", reaches " + fmt("%.1f", ahead) +
           " m along the command, " + fmt("%.1f", side) + " m to the side\n";
  }
  return out;
}

std::string fig10_svg(const Fig10Result& f, const Scene& scene) {
  MapFigure m;
  m.title = "Fig. 10 (" + scene.name + "): future root positions kept in the tree, t = " +
            fmt("%.1f", f.time_s) + " s of the eval recording";
  m.notes = {"same state for every strategy; each grows a fresh tree for " +
                 std::to_string(f.grow_frames) + " frames x " +
                 std::to_string(f.expansions_per_frame) + " expansions (interval " +
                 interval_label(f.interval_s) + ", paper-like rate)",
             "dots: every node's end position; black: avatar and facing; orange: command; grey: "
             "boxes below 1.85 m. Seen from above, x right, z down."};
  // A square view around the avatar that holds every point (plus a margin), inside the bounds.
  double reach = 3.0;
  for (const Fig10Panel& p : f.panels)
    for (const vec2& q : p.end_positions_m)
      reach = std::max(reach, static_cast<double>(glm::length(q - f.avatar.pos_m)));
  reach += 1.0;
  const PlotPoint c{f.avatar.pos_m.x, f.avatar.pos_m.y};
  m.view = {{std::max<double>(c.x - reach, scene.bounds.min_m.x), std::max<double>(c.y - reach, scene.bounds.min_m.y)},
            {std::min<double>(c.x + reach, scene.bounds.max_m.x), std::min<double>(c.y + reach, scene.bounds.max_m.y)}};
  for (const SceneBox& b : scene.boxes)
    if (b.min_m.y < 1.85f)  // boxes a standing body can meet (not high shelves or beams above)
      m.boxes.push_back({{b.min_m.x, b.min_m.z}, {b.max_m.x, b.max_m.z}});
  for (const Fig10Panel& p : f.panels) {
    MapLayer layer;
    layer.name = "(" + std::string(1, static_cast<char>('a' + static_cast<int>(p.strategy))) + ") type " +
                 strategy_title(static_cast<int>(p.strategy)) + ": " +
                 std::to_string(p.end_positions_m.size()) + " nodes";
    for (const vec2& q : p.end_positions_m) layer.points.push_back({q.x, q.y});
    m.panels.push_back(std::move(layer));
  }
  m.avatar = c;
  const vec2 facing(std::sin(f.avatar.heading_rad), std::cos(f.avatar.heading_rad));
  m.avatar_facing = {facing.x, facing.y};
  m.command = {f.command_world.x, f.command_world.y};
  return svg_map_panels(m);
}

// ---- Navigation -----------------------------------------------------------------------------

namespace {

/// The controller's p95 over consecutive blocks of `runs` runs (its rows in order): how much the
/// figure moves with the sample.
std::vector<double> p95_per_block(const NavigationResult& n, const std::string& controller, size_t runs) {
  std::vector<double> out, block;
  size_t in_block = 0;
  for (const NavigationRow& r : n.rows) {
    if (r.controller != controller) continue;
    for (const ResponseRow& e : r.responses) block.push_back(e.ms);
    if (++in_block == runs) {
      out.push_back(percentile(block, 95));
      block.clear();
      in_block = 0;
    }
  }
  return out;
}

constexpr size_t kBlockRuns = 20;

}  // namespace

std::string navigation_text(const NavigationResult& n) {
  const bool replay = n.mode == "replay";
  std::string out = std::string(replay ? "Navigation, recordings replayed open loop"
                                       : "Navigation, closed loop (the scripted player steers each controller live)") +
                    " (interval " + interval_label(n.interval_s) + ", " +
                    std::to_string(n.expansions_per_frame) + " expansions/frame):\n";
  if (replay) {
    out += "  recording  controller                       goal  time s  fallbacks  colliding  "
           "angle deg    tree  resp p50 ms  resp p95 ms\n";
    for (const NavigationRow& r : n.rows) {
      out += "  " + pad(r.recording, 9, false) + "  " + pad(r.controller, 31, false) +
             pad(r.reached_goal ? "yes" : "no", 5) +
             pad(r.reached_goal ? fmt("%.1f", r.time_to_goal_s) : "-", 8) +
             pad(std::to_string(r.fallbacks), 11) + pad(std::to_string(r.colliding_frames), 11) +
             pad(fmt("%.1f", r.mean_command_angle_deg), 11) + pad(fmt("%.1f", r.avg_tree_size), 8) +
             pad(fmt("%.0f", r.response_ms_p50), 13) + pad(fmt("%.0f", r.response_ms_p95), 13) + "\n";
    }
  } else {
    out += "  (" + std::to_string(n.rows.size()) + " runs, one row each in navigation.csv; every response in responses.csv)\n";
  }
  out += std::string(replay ? "Responsiveness, replay" : "Responsiveness, closed loop") +
         " (every run's responses pooled; target p95 < " +
         fmt("%.0f", n.response_target_ms) + " ms):\n";
  for (const ControllerSummary& s : n.summary)
    out += "  " + pad(s.controller, 31, false) + "  goals " + pad(std::to_string(s.goals_reached) + "/" +
           std::to_string(s.recordings), 5) + "  fallbacks " + pad(std::to_string(s.fallbacks), 5) +
           "  stalls " + pad(std::to_string(s.stalls), 4) + "  recoveries " + pad(std::to_string(s.recoveries), 4) +
           "  responses " + pad(std::to_string(s.responses), 4) + "  p50 " + pad(fmt("%.0f", s.response_ms_p50), 5) +
           " ms  p95 " + pad(fmt("%.0f", s.response_ms_p95), 5) + " ms  " +
           (s.response_ms_p95 < n.response_target_ms ? "meets" : "MISSES") + " target\n";
  if (!replay) {
    const std::vector<double> blocks = p95_per_block(n, kResponsiveController, kBlockRuns);
    if (blocks.size() > 1)
      out += std::string("  ") + kResponsiveController + ", p95 per " + std::to_string(kBlockRuns) +
             " seeds: " + bracketed(blocks, [](double v) { return fmt("%.0f", v); }) + " ms\n";
  }
  out += "Collisions over every collision-checking controller (look-ahead 0-4, with steering, greedy): " +
         std::to_string(n.lookahead_collisions) + (n.lookahead_collisions == 0 ? " (as required)\n" : " (MUST BE 0)\n");
  if (n.naive_stuck.empty())
    out += "The naive FSM reached the goal every time.\n";
  else
    out += std::string(replay ? "Naive FSM stuck in recordings: " : "Naive FSM stuck in runs: ") +
           bracketed(n.naive_stuck, [](const std::string& s) { return s; }) +
           "; look-ahead (0-4, with steering) reached the goal in all of them: " +
           (n.lookahead_reached_where_naive_stuck ? "yes" : "NO") + "\n";
  return out;
}

CsvTable navigation_csv(const std::vector<const NavigationResult*>& results) {
  CsvTable csv;
  csv.header = {"mode", "recording", "controller", "lookahead", "reached_goal", "time_to_goal_s",
                "seconds", "fallbacks", "stalls", "recoveries", "colliding_frames", "mean_command_angle_deg",
                "avg_tree_size", "responses", "response_ms_p50", "response_ms_p95"};
  for (const NavigationResult* n : results)
    for (const NavigationRow& r : n->rows)
      csv.rows.push_back({n->mode, r.recording, r.controller, r.lookahead ? "1" : "0", r.reached_goal ? "1" : "0",
                        r.reached_goal ? format_number(r.time_to_goal_s, 3) : "",
                        format_number(r.seconds, 3), std::to_string(r.fallbacks), std::to_string(r.stalls),
                        std::to_string(r.recoveries),
                        std::to_string(r.colliding_frames),
                        format_number(r.mean_command_angle_deg, 2), format_number(r.avg_tree_size, 2),
                        std::to_string(r.responses.size()), format_number(r.response_ms_p50, 1),
                        format_number(r.response_ms_p95, 1)});
  return csv;
}

CsvTable responses_csv(const std::vector<const NavigationResult*>& results) {
  CsvTable csv;
  csv.header = {"mode", "recording", "controller", "at_s", "response_ms", "change_deg",
                "segment_at_change", "segment_at_response"};
  for (const NavigationResult* n : results)
    for (const NavigationRow& r : n->rows)
      for (const ResponseRow& e : r.responses)
        csv.rows.push_back({n->mode, r.recording, r.controller, format_number(e.at_s, 3),
                            format_number(e.ms, 1), format_number(e.change_deg, 1),
                            e.segment_at_change, e.segment_at_response});
  return csv;
}

// ---- JSON and files -------------------------------------------------------------------------

std::string lab_json(const LabResult& r) {
  using bench::Json;
  using bench::rounded;
  auto numbers = [](const std::vector<double>& v, int decimals) {
    Json out = Json::array();
    for (double x : v) out.push_back(rounded(x, decimals));
    return out;
  };
  auto sizes = [&](const TreeSizeTable& t) {
    Json out = Json::object();
    for (int s = 0; s < kNumStrategies; ++s)
      out[std::string(strategy_name(static_cast<Strategy>(s)))] = numbers(t.avg_tree_size[static_cast<size_t>(s)], 2);
    return out;
  };
  const Fig9Result& f = r.fig9;
  const NavigationResult& n = r.navigation;
  Json j = {{"lab", "fig9-fig10-navigation"},
            {"scene", r.scene},
            {"quick", r.options.quick},
            {"frame_cost_s", rounded(f.paper.model.frame_cost_s, 6)},
            {"paper_expansions_per_s", rounded(f.paper.model.expansions_per_s, 0)},
            {"today_expansions_per_s", rounded(f.rate.expansions_per_s, 0)},
            {"intervals_s", numbers(f.paper.intervals_s, 6)},
            {"expansions_per_frame", f.paper.budgets},
            {"avg_tree_size", sizes(f.paper)},
            {"expansions_per_frame_today", f.today.budgets},
            {"avg_tree_size_today", sizes(f.today)}};
  Json& shape = j["fig9_shape"] = Json::array();
  for (const ShapeCheck& c : f.shape) shape.push_back({{"claim", c.claim}, {"holds", c.holds}, {"detail", c.detail}});
  j["turnover_interval_s"] = rounded(f.turnover_interval_s, 6);
  Json& kept = j["kept_share"] = Json::object();
  for (int s = 0; s < kNumStrategies; ++s)
    kept[std::string(strategy_name(static_cast<Strategy>(s)))] =
        rounded(f.turnover[static_cast<size_t>(s)].mean_kept_share, 3);
  Json fig10_sizes = Json::object();
  for (const Fig10Panel& p : r.fig10.panels)
    fig10_sizes[std::string(strategy_name(p.strategy))] = p.end_positions_m.size();
  j["fig10"] = {{"time_s", rounded(r.fig10.time_s, 3)}, {"tree_size", fig10_sizes}};
  j["navigation_interval_s"] = rounded(n.interval_s, 6);
  j["navigation_expansions_per_frame"] = n.expansions_per_frame;
  j["collisions"] = n.lookahead_collisions;
  j["naive_stuck"] = n.naive_stuck;
  j["lookahead_reached_where_naive_stuck"] = n.lookahead_reached_where_naive_stuck;
  auto controllers = [](const NavigationResult& nav) {
    Json out = Json::array();
    for (const ControllerSummary& s : nav.summary)
      out.push_back({{"name", s.controller},
                     {"goals_reached", s.goals_reached},
                     {"recordings", s.recordings},
                     {"fallbacks", s.fallbacks},
                     {"stalls", s.stalls},
                     {"recoveries", s.recoveries},
                     {"colliding_frames", s.colliding_frames},
                     {"response_ms_p50", rounded(s.response_ms_p50, 1)},
                     {"response_ms_p95", rounded(s.response_ms_p95, 1)}});
    return out;
  };
  j["controllers"] = controllers(n);
  const NavigationResult& c = r.closed_loop;
  j["closed_loop"] = {{"collisions", c.lookahead_collisions},
                      {"naive_stuck", c.naive_stuck},
                      {"lookahead_reached_where_naive_stuck", c.lookahead_reached_where_naive_stuck},
                      {"controllers", controllers(c)},
                      {"response_ms_p95_per_20_seeds",
                       numbers(p95_per_block(c, kResponsiveController, kBlockRuns), 1)}};
  // At top level, for quick reading: the responsiveness bar's figure, from the project's
  // responsive controller closed loop (the replays are commands recorded for another avatar),
  // and the paper's controller (look-ahead, command matching re-sorted) on the replays.
  for (const ControllerSummary& s : c.summary)
    if (s.controller == kResponsiveController) {
      j["response_controller"] = s.controller + ", closed loop";
      j["response_ms_p50"] = rounded(s.response_ms_p50, 1);
      j["response_ms_p95"] = rounded(s.response_ms_p95, 1);
      j["response_goals_reached"] = s.goals_reached;
      j["response_runs"] = s.recordings;
    }
  if (r.builtin_closed_loop)
    for (const ControllerSummary& s : r.builtin_closed_loop->summary)
      if (s.controller == kResponsiveController) {
        j["builtin_response_ms_p50"] = rounded(s.response_ms_p50, 1);
        j["builtin_response_ms_p95"] = rounded(s.response_ms_p95, 1);
        j["builtin_response_goals_reached"] = s.goals_reached;
      }
  for (const ControllerSummary& s : n.summary)
    if (s.controller == "look-ahead 1 command") {
      j["paper_response_ms_p50"] = rounded(s.response_ms_p50, 1);
      j["paper_response_ms_p95"] = rounded(s.response_ms_p95, 1);
    }
  if (!r.motion_quality.empty()) {
    Json& quality = j["motion_quality"] = Json::array();
    for (const MotionQualityResult& q : r.motion_quality) {
      nlohmann::json row = motion_quality_json(q);  // keys in alphabetical order
      row["name"] = q.controller;
      quality.push_back(Json(row));
    }
  }
  j["recordings_match_library"] = r.recordings_match_library;
  j["wall_s"] = rounded(r.wall_s, 2);
  return bench::json_line(std::move(j));
}

bool lab_write_files(const LabResult& r, const Scene& scene, const std::filesystem::path& dir,
                     std::string& error) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) {
    error = dir.string() + ": " + ec.message();
    return false;
  }
  return csv_write(dir / "fig9.csv", fig9_csv(r.fig9), error) &&
         write_text(dir / "fig9.svg", fig9_svg(r.fig9, r.scene), error) &&
         csv_write(dir / "fig10.csv", fig10_csv(r.fig10), error) &&
         write_text(dir / "fig10.svg", fig10_svg(r.fig10, scene), error) &&
         csv_write(dir / "navigation.csv", navigation_csv({&r.navigation, &r.closed_loop}), error) &&
         csv_write(dir / "responses.csv", responses_csv({&r.navigation, &r.closed_loop}), error);
}

}  // namespace foresight::lab

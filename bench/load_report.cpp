// foresight-bench load-report: the table and chart of docs/PERFORMANCE.md's load test, from the
// JSON lines `foresight-bots --json` printed for each bot count (scripts/loadtest writes them).
#include "bench_commands.hpp"
#include "bench_json.hpp"
#include "lab/svg_plot.hpp"
#include "machine_info.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace foresight::bench {
namespace {

const char* const kColumns[] = {"bots",          "connected",         "goals_reached",    "collisions",
                                "server_tick_ms_p99", "server_overruns", "tree_size_mean", "rtt_ms_p99",
                                "snapshot_interval_ms_p99", "down_kbps_per_client_p50"};

double number(const nlohmann::json& j, const char* key) {
  const auto it = j.find(key);
  return it != j.end() && it->is_number() ? it->get<double>() : -1.0;
}

}  // namespace

int bench_load_report(const LoadReportOptions& o) {
  std::vector<nlohmann::json> runs;
  for (const std::string& path : o.inputs) {
    std::ifstream in(path);
    if (!in.is_open()) {
      std::fprintf(stderr, "load-report: cannot read %s\n", path.c_str());
      return 1;
    }
    std::string line, last;
    while (std::getline(in, line))
      if (!line.empty() && line.front() == '{') last = line;
    const auto j = nlohmann::json::parse(last, nullptr, false);
    if (j.is_discarded() || !j.is_object()) {
      std::fprintf(stderr, "load-report: %s: no JSON object line (foresight-bots --json output)\n", path.c_str());
      return 1;
    }
    runs.push_back(j);
  }
  if (runs.empty()) {
    std::fprintf(stderr, "load-report: no inputs\n");
    return 1;
  }
  std::sort(runs.begin(), runs.end(),
            [](const auto& a, const auto& b) { return number(a, "bots") < number(b, "bots"); });

  std::ostringstream csv;
  for (const char* c : kColumns) csv << (c == kColumns[0] ? "" : ",") << c;
  csv << "\n";
  print_machine_line();
  std::printf("|");
  for (const char* c : kColumns) std::printf(" %s |", c);
  std::printf("\n|");
  for (size_t i = 0; i < std::size(kColumns); ++i) std::printf("---|");
  std::printf("\n");
  for (const auto& r : runs) {
    std::printf("|");
    for (const char* c : kColumns) {
      const double v = number(r, c);
      std::printf(" %.*f |", v == std::floor(v) ? 0 : 2, v);
      csv << (c == kColumns[0] ? "" : ",") << v;
    }
    std::printf("\n");
    csv << "\n";
  }
  std::error_code ec;
  std::filesystem::create_directories(o.out_dir, ec);
  std::ofstream(std::filesystem::path(o.out_dir) / "loadtest.csv") << csv.str();

  lab::LineChart chart;
  chart.title = "Load test: server tick time and tree size against bots";
  chart.x_label = "bots";
  chart.y_label = "ms (tick p99) / nodes / 10 (tree size mean)";
  chart.notes.push_back(machine_description());
  lab::LineSeries tick{"server_tick_ms_p99", {}, false}, tree{"tree_size_mean / 10", {}, true},
      budget{"tick period (33.3 ms)", {}, true};
  for (const auto& r : runs) {
    const double bots = number(r, "bots");
    tick.points.push_back({bots, number(r, "server_tick_ms_p99")});
    tree.points.push_back({bots, number(r, "tree_size_mean") / 10.0});
    budget.points.push_back({bots, 1000.0 / 30.0});
  }
  chart.series = {tick, tree, budget};
  std::ofstream(std::filesystem::path(o.out_dir) / "loadtest.svg") << lab::svg_line_chart(chart);
  std::printf("wrote %s/loadtest.csv and loadtest.svg\n", o.out_dir.c_str());
  return 0;
}

}  // namespace foresight::bench

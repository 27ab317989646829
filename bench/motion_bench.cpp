// bvh and graph: the offline half (loading and graph building), timed.
#include "import/bvh_import.hpp"
#include "bench_commands.hpp"
#include "bench_json.hpp"
#include "library_build/library_source.hpp"

#include <chrono>
#include <cstdio>

namespace foresight::bench {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

std::filesystem::path largest_mocap_file() {
  std::filesystem::path best;
  std::error_code ec;
  for (const auto& e : std::filesystem::recursive_directory_iterator(FORESIGHT_MOCAP_DIR, ec))
    if (e.path().extension() == ".bvh" &&
        (best.empty() || e.file_size() > std::filesystem::file_size(best)))
      best = e.path();
  return best;
}

}  // namespace

int bench_bvh(const BvhBenchOptions& o) {
  const std::filesystem::path file = o.file.empty() ? largest_mocap_file() : std::filesystem::path(o.file);
  if (file.empty()) {
    std::fprintf(stderr, "foresight-bench bvh: no --file and no ../shared/mocap\n");
    return 2;
  }
  std::vector<double> parse_ms, import_ms;
  int frames = 0;
  for (int run = 0; run < o.runs; ++run) {
    BvhDocument doc;
    Skeleton skeleton;
    Clip clip;
    std::string error;
    auto t0 = Clock::now();
    if (!bvh_load(file, doc, error)) return std::fprintf(stderr, "%s\n", error.c_str()), 1;
    parse_ms.push_back(ms_since(t0));
    t0 = Clock::now();
    if (!clip_from_bvh(doc, "bench", {}, skeleton, clip, nullptr, error))
      return std::fprintf(stderr, "%s\n", error.c_str()), 1;
    import_ms.push_back(ms_since(t0));
    frames = clip.num_frames;
  }
  const double size_kib = static_cast<double>(std::filesystem::file_size(file)) / 1024.0;
  const double p = median(parse_ms), i = median(import_ms);
  print_machine_line();
  std::printf("%s (%.0f KiB, %d frames): parse %.2f ms, import %.2f ms (median of %d)\n",
              file.filename().c_str(), size_kib, frames, p, i, o.runs);
  if (o.json)
    print_json_line({{"bench", "bvh"},
                     {"file", file.filename().string()},
                     {"kib", rounded(size_kib, 0)},
                     {"frames", frames},
                     {"parse_ms", rounded(p, 3)},
                     {"import_ms", rounded(i, 3)},
                     {"parse_mib_per_sec", rounded(size_kib / 1024.0 / (p / 1000.0), 1)}});
  return 0;
}

int bench_graph(const GraphBenchOptions& o) {
  std::vector<double> build_ms;
  LibraryImportReport imported;
  const AutoGraphReport& report = imported.graph;
  MotionSource source;
  source.motions_dir = o.motions;
  size_t clips = 0, frames = 0;
  for (int run = 0; run < o.runs; ++run) {
    MotionLibrary lib;
    std::string error;
    const auto t0 = Clock::now();
    if (!motion_library_from_folder(source, lib, &imported, error))
      return std::fprintf(stderr, "foresight-bench graph: %s\n", error.c_str()), 1;
    build_ms.push_back(ms_since(t0));
    clips = lib.clips.size();
    frames = 0;
    for (const Clip& c : lib.clips) frames += static_cast<size_t>(c.num_frames);
  }
  const double ms = median(build_ms);
  print_machine_line();
  std::printf("%zu clips, %zu frames: load + automatic graph + compile %.0f ms (median of %d); "
              "%lld frame pairs compared (%.1f M/s); graph %d nodes, %d edges\n",
              clips, frames, ms, o.runs, report.frame_pairs_compared,
              static_cast<double>(report.frame_pairs_compared) / (ms * 1000.0), report.segments,
              report.edges);
  if (o.json)
    print_json_line({{"bench", "graph"},
                     {"clips", clips},
                     {"frames", frames},
                     {"build_ms", rounded(ms, 1)},
                     {"frame_pairs", report.frame_pairs_compared},
                     {"nodes", report.segments},
                     {"edges", report.edges}});
  return 0;
}

}  // namespace foresight::bench

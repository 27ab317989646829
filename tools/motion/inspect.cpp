// info, graph and export-bvh: read-only views of a library.
#include "anim/bvh.hpp"
#include "commands.hpp"

#include <cinttypes>
#include <cstdio>

namespace foresight::tools {

bool load_library_or_report(const MotionSource& source, MotionLibrary& lib) {
  std::string error;
  if (motion_library_load(source, lib, error)) return true;
  std::fprintf(stderr, "foresight-motion: %s\n", error.c_str());
  return false;
}

int command_info(const MotionSource& source, bool brief) {
  MotionLibrary lib;
  if (!load_library_or_report(source, lib)) return 1;
  std::printf("library %s: %d joints, %zu clips, %d segments, %zu transitions, hash %016" PRIx64 "\n",
              lib.name.c_str(), lib.num_joints(), lib.clips.size(), lib.graph.num_segments(),
              lib.graph.transitions.size(), lib.content_hash);
  if (brief) return 0;
  for (int s = 0; s < lib.graph.num_segments(); ++s) {
    const Segment& seg = lib.graph.segments[s];
    const SegmentMotion& m = lib.segment_motion[s];
    std::printf("  %-28s %3d frames  r=(%+.2f, %+.2f) m  turn %+6.1f deg  -> %zu successors\n",
                seg.name.c_str(), seg.num_frames(), m.end.pos_m.x, m.end.pos_m.y,
                degrees(m.end.heading_rad), lib.graph.successors(s).size());
  }
  return 0;
}

int command_graph(const MotionSource& source) {
  if (source.motions_dir.empty()) {
    std::fprintf(stderr, "foresight-motion graph: needs --motions DIR (the default library's graph "
                         "is declared; see `info`)\n");
    return 2;
  }
  MotionLibrary lib;
  AutoGraphReport r;
  std::string error;
  if (!motion_library_from_folder(source.motions_dir, source.import, source.graph, lib, &r, error)) {
    std::fprintf(stderr, "foresight-motion: %s\n", error.c_str());
    return 1;
  }
  std::printf("%zu clips; %lld frame pairs compared; %d local minima below %.3f m RMS; "
              "%d transitions accepted\n",
              lib.clips.size(), r.frame_pairs_compared, r.local_minima, source.graph.threshold_rms_m,
              r.transitions_accepted);
  std::printf("before pruning: %d nodes, %d edges; largest strongly connected component: "
              "%d nodes, %d edges\n",
              r.segments_before_prune, r.edges_before_prune, r.segments, r.edges);
  return 0;
}

int command_export_bvh(const MotionSource& source, const std::string& out_dir) {
  MotionLibrary lib;
  if (!load_library_or_report(source, lib)) return 1;
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  for (const Clip& clip : lib.clips) {
    const auto path = std::filesystem::path(out_dir) / (clip.name + ".bvh");
    std::string error;
    if (!bvh_save(path, bvh_from_clip(lib.skeleton, clip), error)) {
      std::fprintf(stderr, "foresight-motion: %s\n", error.c_str());
      return 1;
    }
  }
  std::printf("wrote %zu clips to %s\n", lib.clips.size(), out_dir.c_str());
  return 0;
}

}  // namespace foresight::tools

// info, graph and export-bvh: read-only views of a library.
#include "import/bvh.hpp"
#include "commands.hpp"
#include "library/steerability.hpp"

#include <nlohmann/json.hpp>

#include <cinttypes>
#include <cstdio>

namespace foresight::tools {

bool load_library_or_report(const MotionSource& source, MotionLibrary& lib) {
  std::string error;
  if (motion_library_load(source, lib, error)) return true;
  std::fprintf(stderr, "foresight-motion: %s\n", error.c_str());
  return false;
}

namespace {

nlohmann::json clip_import_json(const ClipImport& c, const Skeleton& library_skeleton) {
  const BvhImportReport& r = c.import;
  nlohmann::json j{{"file", c.file}, {"kept", c.kept}};
  if (!c.kept) j["reason"] = c.reason;
  if (r.source_frames == 0) return j;  // did not parse
  std::vector<std::string> kept, dropped;
  for (size_t k = 0; k < r.source_joints.size(); ++k)
    (r.source_joint_kept[k] ? kept : dropped).push_back(r.source_joints[k]);
  nlohmann::json mapping = nlohmann::json::object();
  for (size_t k = 0; k < r.source_joints.size(); ++k)
    if (r.canonical_joint[k] >= 0)
      mapping[r.source_joints[k]] = library_skeleton.joint_names.empty()
                                        ? std::to_string(r.canonical_joint[k])
                                        : library_skeleton.joint_names[static_cast<size_t>(r.canonical_joint[k])];
  j.update({{"scale_m_per_unit", r.scale},
            {"unit", r.unit == LengthUnit::kAuto ? "none" : std::string(length_unit_name(r.unit))},
            {"height_normalised", r.height_normalised},
            {"root", std::string(root_position_name(r.root))},
            {"up", std::string(up_axis_name(r.up))},
            {"source_fps", r.source_fps},
            {"fps", r.fps},
            {"source_frames", r.source_frames},
            {"folded_root_joints", r.folded_root_joints},
            {"humanoid", r.humanoid},
            {"standing_height_m", r.standing_height_m},
            {"head_height_m", r.head_height_m},
            {"lowest_foot_m", r.lowest_foot_m},
            {"stride_scale", c.root_scale},
            {"joints_kept", kept},
            {"joints_dropped", dropped},
            {"joint_map", mapping},
            {"warnings", r.warnings}});
  if (!r.humanoid) j["not_humanoid"] = r.not_humanoid;
  return j;
}

void print_clip_import(const nlohmann::json& j) {
  std::printf("%s: %s\n", j["file"].get<std::string>().c_str(),
              j["kept"].get<bool>() ? "kept" : ("skipped: " + j["reason"].get<std::string>()).c_str());
  if (!j.contains("scale_m_per_unit")) return;
  const std::string unit = j["unit"];
  std::printf("  scale %.5f m/unit (%s%s), root %s, up %s, %.0f -> %.0f fps, %d frames, %d dummy roots folded\n",
              j["scale_m_per_unit"].get<float>(), j["height_normalised"].get<bool>() ? "height normalised, unit looks like " : "",
              unit.c_str(), j["root"].get<std::string>().c_str(), j["up"].get<std::string>().c_str(),
              j["source_fps"].get<float>(), j["fps"].get<float>(), j["source_frames"].get<int>(),
              j["folded_root_joints"].get<int>());
  if (j["humanoid"].get<bool>())
    std::printf("  standing height %.3f m (head end %.3f m), lowest foot %+.3f m (median), stride x%.3f; joints kept %zu, dropped %zu%s\n",
                j["standing_height_m"].get<float>(), j["head_height_m"].get<float>(), j["lowest_foot_m"].get<float>(), j["stride_scale"].get<float>(),
                j["joints_kept"].size(), j["joints_dropped"].size(), j["joints_dropped"].empty() ? "" : ":");
  else
    std::printf("  not a humanoid: %s\n", j["not_humanoid"].get<std::string>().c_str());
  if (!j["joints_dropped"].empty()) {
    std::string names;
    for (const auto& n : j["joints_dropped"]) names += " " + n.get<std::string>();
    std::printf("   %s\n", names.c_str());
  }
  for (const auto& w : j["warnings"]) std::printf("  WARNING: %s\n", w.get<std::string>().c_str());
}

}  // namespace

int command_info(const MotionSource& source, bool brief, bool json) {
  MotionLibrary lib;
  LibraryImportReport report;
  std::string error;
  const bool loaded = source.motions_dir.empty() ? (lib = motion_library_default(), true)
                                                 : motion_library_from_folder(source, lib, &report, error);
  nlohmann::json clips = nlohmann::json::array();
  for (const ClipImport& c : report.files) clips.push_back(clip_import_json(c, lib.skeleton));
  if (json) {
    nlohmann::json out{{"library", loaded ? lib.name : ""}, {"loaded", loaded}, {"clips", clips}};
    if (loaded)
      out.update({{"joints", lib.num_joints()}, {"segments", lib.graph.num_segments()},
                  {"transitions", lib.graph.transitions.size()}, {"content_hash", lib.content_hash}});
    else
      out["error"] = error;
    std::printf("%s\n", out.dump().c_str());
    return loaded ? 0 : 1;
  }
  for (const auto& c : clips) print_clip_import(c);
  if (!loaded) {
    std::fprintf(stderr, "foresight-motion: %s\n", error.c_str());
    return 1;
  }
  std::printf("library %s: %d joints, %zu clips, %d segments, %zu transitions, hash %016" PRIx64 "\n",
              lib.name.c_str(), lib.num_joints(), lib.clips.size(), lib.graph.num_segments(),
              lib.graph.transitions.size(), lib.content_hash);
  if (brief) return 0;
  for (int s = 0; s < lib.graph.num_segments(); ++s) {
    const Segment& seg = lib.graph.segments[s];
    const SegmentMotion& m = lib.segment_motion[s];
    const SegmentBody body = segment_body(lib, s);
    std::printf("  %-28s %3d frames  r=(%+.2f, %+.2f) m  turn %+6.1f deg  body %.2f x %.2f x %.2f m  -> %zu successors\n",
                seg.name.c_str(), seg.num_frames(), m.end.pos_m.x, m.end.pos_m.y,
                degrees(m.end.heading_rad), body.width_m, body.length_m, body.height_m,
                lib.graph.successors(s).size());
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
  LibraryImportReport report;
  std::string error;
  if (!motion_library_from_folder(source, lib, &report, error)) {
    std::fprintf(stderr, "foresight-motion: %s\n", error.c_str());
    return 1;
  }
  const AutoGraphReport& r = report.graph;
  std::printf("%zu clips; %lld frame pairs compared; %d local minima below %.3f m RMS; "
              "%d transitions accepted, %d clip ends continued into starts\n",
              lib.clips.size(), r.frame_pairs_compared, r.local_minima, source.graph.threshold_rms_m,
              r.transitions_accepted, r.clip_joins);
  std::printf("before pruning: %d nodes, %d edges; with derived motion, largest strongly connected "
              "component: %d nodes, %d edges\n",
              r.segments_before_prune, r.edges_before_prune, r.segments, r.edges);
  const DerivedMotionReport& d = report.derived;
  auto has = [](bool b) { return b ? "yes" : "NO"; };
  std::printf("the capture has: a stand %s, a turn on the spot %s, a stop %s, a start %s\n", has(d.captured_idle),
              has(d.captured_turn_on_spot), has(d.captured_stop), has(d.captured_start));
  std::printf("derived: standing pose from %s frame %d (pelvis %.2f m/s), "
              "%d idle loop, %d turns on the spot, %d stops, %d starts, %d bent walking pieces\n",
              d.standing_clip.c_str(), d.standing_frame, d.standing_speed_m_per_s, d.idles, d.turns, d.stops, d.starts,
              d.bends);
  for (const ClipInGraph& c : report.clips) {
    if (c.derived) continue;
    if (c.segments_kept > 0)
      std::printf("  kept    %-48s %d of %d segments\n", c.clip.c_str(), c.segments_kept, c.segments);
    else
      std::printf("  DROPPED %-48s %s\n", c.clip.c_str(), c.dropped_why.c_str());
  }
  for (const ClipImport& f : report.files)
    if (!f.kept) std::printf("  SKIPPED %-48s %s\n", f.file.c_str(), f.reason.c_str());
  const struct {
    const char* what;
    int segment;
  } starts[] = {{"standing", standing_segment(lib)}, {"walking", walking_segment(lib)}};
  for (const auto& s : starts) {
    const auto can = followable_directions(lib, s.segment);
    std::string line;
    for (int k = 0; k < kCommandSectors; ++k)
      line += std::string(" ") + std::string(command_sector_name(k)) + (can[static_cast<size_t>(k)] ? " yes," : " NO,");
    line.pop_back();
    std::printf("from %s (%s):%s\n", s.what, s.segment >= 0 ? lib.graph.segments[static_cast<size_t>(s.segment)].name.c_str() : "none",
                line.c_str());
  }
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

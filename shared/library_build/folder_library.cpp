#include "library_build/library_compile.hpp"
#include "library_build/library_source.hpp"

#include "import/humanoid_retarget.hpp"
#include "graph_build/graph_edit.hpp"

#include <algorithm>
#include <cmath>

namespace foresight {
namespace {

// Tags for clips nobody annotated, from how fast the root moves and how low the pelvis goes (the
// auto graph knows nothing else): idle below 0.2 m/s, run above 2.2 m/s, crouch when the pelvis
// spends most of the clip under 78 % of its standing height (a crouch-walk's is about 65 %).
uint32_t tags_of_clip(const MotionLibrary& lib, int clip) {
  const Clip& c = lib.clips[clip];
  const Placement a = lib.root_placement(clip, 0), b = lib.root_placement(clip, c.num_frames - 1);
  const float speed = glm::length(b.pos_m - a.pos_m) / std::max(c.duration_s(), 1e-3f);
  std::vector<float> heights;
  for (int f = 0; f < c.num_frames; ++f) heights.push_back(c.frame_pos(f)[0].y);
  std::nth_element(heights.begin(), heights.begin() + heights.size() / 2, heights.end());
  const uint32_t crouch = heights[heights.size() / 2] < 0.78f * lib.skeleton.rest_offsets_m[0].y ? kTagCrouch : 0u;
  if (speed < 0.2f) return kTagIdle | crouch;
  return kTagLocomotion | crouch | (speed > 2.2f ? kTagRun : 0u);
}


// Step 1: every file imported onto the canonical skeleton, the first usable one's body the
// library's; other bodies are retargeted onto it, striding in proportion to the legs.
void import_clips(const MotionSource& source, const std::vector<std::filesystem::path>& files,
                  MotionLibrarySource& lib, LibraryImportReport& rep) {
  BvhImportOptions import = source.import;
  import.canonical = true;
  float library_leg_m = 0.0f;
  for (const auto& file : files) {
    ClipImport& c = rep.files.emplace_back();
    c.file = file.filename().string();
    Skeleton skeleton;
    Clip clip;
    BvhImportOptions options = import;
    if (!lib.clips.empty()) options.target_fps = lib.clips[0].fps;  // every clip at the library's rate
    if (!clip_load_bvh(file, options, skeleton, clip, &c.import, c.reason)) continue;
    if (lib.clips.empty()) {
      lib.skeleton = std::move(skeleton);
      library_leg_m = canonical_leg_length(lib.skeleton);
    } else if (skeleton.rest_offsets_m != lib.skeleton.rest_offsets_m) {
      c.root_scale = library_leg_m / canonical_leg_length(skeleton);
      Clip onto;
      retarget_to_canonical(skeleton, clip, canonical_humanoid_map(), lib.skeleton, c.root_scale, onto);
      clip = std::move(onto);
    }
    c.kept = true;
    lib.clips.push_back(std::move(clip));
  }
}

// Step 3: the graph pruned to its largest strongly connected component, what it kept of each clip
// reported, and derived clips whose pieces it dropped removed (captured clips stay: their files
// were read, the report names them).
void prune(MotionGraph graph, size_t captured, MotionLibrarySource& lib, LibraryImportReport& rep) {
  rep.clips.resize(lib.clips.size());
  for (size_t c = 0; c < lib.clips.size(); ++c) rep.clips[c] = {lib.clips[c].name, c >= captured, 0, 0, {}};
  for (const Segment& s : graph.segments) ++rep.clips[static_cast<size_t>(s.clip)].segments;
  lib.graph = graph_keep_segments(graph, largest_strongly_connected_component(graph));
  for (const Segment& s : lib.graph.segments) ++rep.clips[static_cast<size_t>(s.clip)].segments_kept;
  for (ClipInGraph& c : rep.clips)
    if (c.segments_kept == 0)
      c.dropped_why = c.segments == 0 ? "shorter than a transition window"
                                      : "no way into it and back out (no transition within the threshold, no stop or start)";
  std::vector<int> new_index(lib.clips.size(), -1);
  std::vector<Clip> kept_clips;
  std::vector<uint32_t> kept_tags;
  for (size_t c = 0; c < lib.clips.size(); ++c) {
    if (c >= captured && rep.clips[c].segments_kept == 0) continue;
    new_index[c] = static_cast<int>(kept_clips.size());
    kept_clips.push_back(std::move(lib.clips[c]));
    kept_tags.push_back(lib.clip_tags[c]);
  }
  lib.clips = std::move(kept_clips);
  lib.clip_tags = std::move(kept_tags);
  for (Segment& s : lib.graph.segments) s.clip = new_index[static_cast<size_t>(s.clip)];
  rep.graph.segments = lib.graph.num_segments();
  rep.graph.edges = static_cast<int>(lib.graph.transitions.size());
}

}  // namespace

bool motion_library_from_folder(const MotionSource& source, MotionLibrary& out,
                                LibraryImportReport* report, std::string& error) {
  const std::filesystem::path& dir = source.motions_dir;
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec))
    return error = dir.string() + ": not a folder of BVH files", false;
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    std::string ext = entry.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    if (entry.is_regular_file() && ext == ".bvh") files.push_back(entry.path());
  }
  if (ec) return error = dir.string() + ": " + ec.message(), false;
  if (files.empty()) return error = dir.string() + ": no .bvh files", false;
  std::sort(files.begin(), files.end());

  LibraryImportReport rep;
  MotionLibrarySource lib;
  lib.name = dir.filename().string();
  import_clips(source, files, lib, rep);
  if (report) *report = rep;
  for (const ClipImport& c : rep.files)
    if (!c.kept && source.strict) return error = c.reason + " (--strict)", false;
  if (lib.clips.empty()) {
    error = dir.string() + ": no usable humanoid clip";
    for (const ClipImport& c : rep.files) error += "\n  " + c.reason;
    return false;
  }

  // Step 2: the automatic graph, unpruned, its segments cut to half a second at most between
  // decisions (as in the built-in library's half-gait steps), and what steering needs derived.
  AutoGraphOptions graph_options = source.graph;
  graph_options.prune_to_largest_component = false;
  MotionGraph graph;
  if (!graph_build_automatic(lib.skeleton, lib.clips, graph_options, graph, &rep.graph, error))
    return error = dir.string() + ": " + error, false;
  graph = graph_split_long_segments(graph, static_cast<int>(std::lround(0.5f * lib.clips[0].fps)));
  const size_t captured = lib.clips.size();
  lib.clip_tags.assign(captured, kTagLocomotion);
  derive_steering_motion(lib.skeleton, lib.clips, lib.clip_tags, graph, rep.derived);
  prune(std::move(graph), captured, lib, rep);
  if (report) *report = rep;
  if (rep.graph.segments < 2)
    return error = dir.string() + ": the motion graph's largest strongly connected component has " +
                   std::to_string(rep.graph.segments) + " segments; raise --threshold", false;

  // Step 4: compile; tag captured clips from the compiled root tracks, then recompile so segments
  // and hash carry the tags.
  MotionLibrary first;
  if (!motion_library_compile(std::move(lib), first, error)) return false;
  std::vector<uint32_t> tags = first.clip_tags;
  for (size_t c = 0; c < captured; ++c) tags[c] = tags_of_clip(first, static_cast<int>(c));
  MotionLibrarySource tagged = std::move(static_cast<MotionLibrarySource&>(first));
  tagged.clip_tags = std::move(tags);
  for (Segment& s : tagged.graph.segments) s.tags = tagged.clip_tags[static_cast<size_t>(s.clip)];
  return motion_library_compile(std::move(tagged), out, error);
}

bool motion_library_load(const MotionSource& source, MotionLibrary& out, std::string& error) {
  if (source.motions_dir.empty()) {
    out = motion_library_default();
    return true;
  }
  return motion_library_from_folder(source, out, nullptr, error);
}

}  // namespace foresight

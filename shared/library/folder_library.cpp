#include "library/library_source.hpp"

#include <algorithm>

namespace foresight {
namespace {

// Tags for clips nobody annotated, from how fast the root moves (the auto graph knows nothing else).
uint32_t tags_from_speed(const MotionLibrary& lib, int clip) {
  const Clip& c = lib.clips[clip];
  const Placement a = lib.root_placement(clip, 0), b = lib.root_placement(clip, c.num_frames - 1);
  const float speed = glm::length(b.pos_m - a.pos_m) / std::max(c.duration_s(), 1e-3f);
  if (speed < 0.2f) return kTagIdle;
  return kTagLocomotion | (speed > 2.2f ? kTagRun : 0u);
}

bool same_topology(const Skeleton& a, const Skeleton& b) {
  return a.joint_names == b.joint_names && a.parents == b.parents;
}

}  // namespace

bool motion_library_from_folder(const std::filesystem::path& dir, const BvhImportOptions& import,
                                const AutoGraphOptions& graph, MotionLibrary& out,
                                AutoGraphReport* report, std::string& error) {
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

  MotionLibrary lib;
  lib.name = dir.filename().string();
  for (const auto& file : files) {
    Skeleton skeleton;
    Clip clip;
    if (!clip_load_bvh(file, import, skeleton, clip, nullptr, error)) return false;
    if (lib.clips.empty()) {
      lib.skeleton = std::move(skeleton);
    } else if (!same_topology(lib.skeleton, skeleton)) {
      return error = file.string() + ": skeleton differs from " + files[0].filename().string() +
                     " (joint names or hierarchy)",
             false;
    } else if (clip.fps != lib.clips[0].fps) {
      return error = file.string() + ": " + std::to_string(clip.fps) + " fps after import, " +
                     files[0].filename().string() + " has " + std::to_string(lib.clips[0].fps),
             false;
    }
    lib.clips.push_back(std::move(clip));
  }
  if (!graph_build_automatic(lib.skeleton, lib.clips, graph, lib.graph, report, error))
    return error = dir.string() + ": " + error, false;
  lib.clip_tags.assign(lib.clips.size(), kTagLocomotion);
  if (!motion_library_compile(lib, error)) return false;
  // Tag from the compiled root tracks, then recompile so segments and hash carry the tags.
  for (size_t c = 0; c < lib.clips.size(); ++c) lib.clip_tags[c] = tags_from_speed(lib, static_cast<int>(c));
  for (Segment& s : lib.graph.segments) s.tags = lib.clip_tags[s.clip];
  if (!motion_library_compile(lib, error)) return false;
  out = std::move(lib);
  return true;
}

bool motion_library_load(const MotionSource& source, MotionLibrary& out, std::string& error) {
  if (source.motions_dir.empty()) {
    out = motion_library_default();
    return true;
  }
  return motion_library_from_folder(source.motions_dir, source.import, source.graph, out, nullptr,
                                    error);
}

}  // namespace foresight

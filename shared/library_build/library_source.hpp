#pragma once
// Where a MotionLibrary comes from: the built-in default (procedurally authored, no files needed)
// or a folder of BVH clips with an automatically built graph (`--motions DIR` on every binary).
#include "import/bvh_import.hpp"
#include "graph_build/auto_graph.hpp"
#include "library_build/derived_motion.hpp"
#include "library/motion_library.hpp"

#include <filesystem>

namespace foresight {

struct MotionSource {
  std::filesystem::path motions_dir;  ///< Empty: the built-in default library.
  BvhImportOptions import;            ///< For folders (always retargeted to the canonical skeleton).
  AutoGraphOptions graph;             ///< For folders.
  bool strict = false;  ///< A file that cannot be used fails the folder instead of being skipped.
};

/// What became of one file of a folder.
struct ClipImport {
  std::string file;        ///< File name within the folder.
  bool kept = false;       ///< Imported into the library (false: skipped, `reason` says why).
  std::string reason;
  BvhImportReport import;  ///< What the import decided (when the file parsed).
  float root_scale = 1.0f; ///< Stride scale onto the library's body (another actor's proportions).
};

/// What the graph kept of one clip.
struct ClipInGraph {
  std::string clip;
  bool derived = false;       ///< Made by derive_steering_motion, not captured.
  int segments = 0;           ///< Cut into, before pruning.
  int segments_kept = 0;      ///< In the graph's largest strongly connected component.
  std::string dropped_why;    ///< When none was kept.
};

struct LibraryImportReport {
  std::vector<ClipImport> files;  ///< Sorted by name, every .bvh of the folder.
  AutoGraphReport graph;
  DerivedMotionReport derived;
  std::vector<ClipInGraph> clips;  ///< Per library clip, captured then derived.
};

/// The built-in default library: authored clips, the manifest's declared graph, compiled.
/// Deterministic: the same content hash on every machine.
MotionLibrary motion_library_default();

/// Every *.bvh directly in `source.motions_dir` (sorted by name), imported, normalised and
/// retargeted onto the canonical skeleton with the first usable file's proportions (files of
/// other skeletons, actors, units and frame rates mix), with the automatic graph. A file that is
/// not a usable humanoid is skipped and the report says why (with `strict`, it fails the folder).
/// Fails when no file is usable or nothing connects.
bool motion_library_from_folder(const MotionSource& source, MotionLibrary& out,
                                LibraryImportReport* report, std::string& error);

/// Either of the above, as `source` says.
bool motion_library_load(const MotionSource& source, MotionLibrary& out, std::string& error);

}  // namespace foresight

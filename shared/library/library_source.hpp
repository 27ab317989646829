#pragma once
// Where a MotionLibrary comes from: the built-in default (procedurally authored, no files needed)
// or a folder of BVH clips with an automatically built graph (`--motions DIR` on every binary).
#include "anim/bvh_import.hpp"
#include "graph/auto_graph.hpp"
#include "library/motion_library.hpp"

#include <filesystem>

namespace foresight {

struct MotionSource {
  std::filesystem::path motions_dir;  ///< Empty: the built-in default library.
  BvhImportOptions import;            ///< For folders.
  AutoGraphOptions graph;             ///< For folders.
};

/// The built-in default library: authored clips, the manifest's declared graph, compiled.
/// Deterministic: the same content hash on every machine.
MotionLibrary motion_library_default();

/// Every *.bvh directly in `dir` (sorted by name), imported and normalised, on one skeleton
/// topology (same joint names in the same order; bone lengths may differ per clip), with the
/// automatic graph. Fails with a reason naming the file on a bad clip or a different skeleton.
bool motion_library_from_folder(const std::filesystem::path& dir, const BvhImportOptions& import,
                                const AutoGraphOptions& graph, MotionLibrary& out,
                                AutoGraphReport* report, std::string& error);

/// Either of the above, as `source` says.
bool motion_library_load(const MotionSource& source, MotionLibrary& out, std::string& error);

}  // namespace foresight

#pragma once
// The motion-library options every binary takes (--motions DIR, --threshold, --bvh-units,
// --bvh-scale, --bvh-root, --bvh-up, --strict), declared once. Header-only: only executables include it (they link CLI11).
#include "library_build/library_source.hpp"

#include <CLI/CLI.hpp>

#include <map>
#include <string>

namespace foresight {

/// Adds the options to `app`; after parsing, `source` describes the library to load.
inline void add_motion_source_options(CLI::App& app, MotionSource& source) {
  app.add_option("--motions", source.motions_dir,
                 "Folder of BVH clips to use instead of the built-in default library")
      ->check(CLI::ExistingDirectory);
  app.add_option("--threshold", source.graph.threshold_rms_m,
                 "Automatic graph: max RMS point distance of a transition, metres")
      ->check(CLI::Range(0.001, 10.0));
  static const std::map<std::string, LengthUnit> units{
      {"auto", LengthUnit::kAuto},         {"m", LengthUnit::kMetres},
      {"cm", LengthUnit::kCentimetres},    {"mm", LengthUnit::kMillimetres},
      {"in", LengthUnit::kInches},         {"ft", LengthUnit::kFeet}};
  static const std::map<std::string, RootPosition> roots{{"auto", RootPosition::kAuto},
                                                         {"absolute", RootPosition::kAbsolute},
                                                         {"relative", RootPosition::kRelative}};
  static const std::map<std::string, UpAxis> ups{{"auto", UpAxis::kAuto}, {"y", UpAxis::kYUp},
                                                 {"z", UpAxis::kZUp}, {"x", UpAxis::kXUp}};
  app.add_option("--bvh-units", source.import.unit,
                 "Length unit of the BVH files, keeping the actor's true size (default: the standing "
                 "height is scaled to the canonical skeleton's)")
      ->transform(CLI::CheckedTransformer(units, CLI::ignore_case));
  app.add_option("--bvh-scale", source.import.scale, "Metres per BVH file unit (wins over --bvh-units)")
      ->check(CLI::PositiveNumber);
  app.add_option("--bvh-root", source.import.root,
                 "Root position channels: absolute, relative (to the ROOT OFFSET) or auto (the "
                 "reading that keeps the feet on the floor)")
      ->transform(CLI::CheckedTransformer(roots, CLI::ignore_case));
  app.add_flag("--strict", source.strict, "Refuse a folder with any unusable file (default: skip it)");
  app.add_option("--bvh-up", source.import.up, "Up axis of the BVH files (default: detected)")
      ->transform(CLI::CheckedTransformer(ups, CLI::ignore_case));
}

}  // namespace foresight

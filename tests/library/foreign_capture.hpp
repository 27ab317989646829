#pragma once
// Capture the team did not make, made more foreign still: the Bandai takes rescaled to inches
// under a dummy root (and, if asked, with their rotation channels reordered), written to a
// scratch folder and compiled with no unit hint, as a studio's export would arrive.
#include "import/bvh.hpp"
#include "library_build/library_source.hpp"
#include "support/bvh_variants.hpp"
#include "support/test_paths.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace foresight::test {

/// A take in inches (the unit the file does not say) under a dummy root joint.
inline void make_foreign(BvhDocument& take) {
  scale_document(take, 1.0f / 2.54f);
  insert_parent(take, 0, "Reference", 0.0f);
}

/// Fails the calling test (use ASSERT_NO_FATAL_FAILURE) when the take or the library does not load.
inline void foreign_walk_library(const std::string& rotation_order, MotionLibrary& lib) {
  BvhDocument take;
  std::string error;
  ASSERT_TRUE(bvh_load(mocap_dir() / "locomotion" / "bandai_dataset-1_walk_normal_001.bvh", take, error)) << error;
  make_foreign(take);
  if (!rotation_order.empty()) reorder_rotations(take, rotation_order);
  const auto dir = scratch_dir();
  ASSERT_TRUE(bvh_save(dir / "walk_variant.bvh", take, error)) << error;
  MotionSource source;
  source.motions_dir = dir;
  ASSERT_TRUE(motion_library_from_folder(source, lib, nullptr, error)) << error;
}

/// Every Bandai locomotion take made foreign that way (no reordering): a whole library, with its
/// starts, stops and turns. Fails the calling test when a take or the library does not load.
inline void foreign_locomotion_library(MotionLibrary& lib) {
  const auto dir = scratch_dir();
  int takes = 0;
  std::string error;
  for (const auto& entry : std::filesystem::directory_iterator(mocap_dir() / "locomotion")) {
    if (entry.path().extension() != ".bvh") continue;
    BvhDocument take;
    ASSERT_TRUE(bvh_load(entry.path(), take, error)) << error;
    make_foreign(take);
    ASSERT_TRUE(bvh_save(dir / entry.path().filename(), take, error)) << error;
    ++takes;
  }
  ASSERT_GT(takes, 10);
  MotionSource source;
  source.motions_dir = dir;
  ASSERT_TRUE(motion_library_from_folder(source, lib, nullptr, error)) << error;
}

}  // namespace foresight::test

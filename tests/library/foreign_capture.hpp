#pragma once
// Capture the team did not make, made more foreign still: the Bandai normal walk rescaled to
// inches under a dummy root (and, if asked, with its rotation channels reordered), written to a
// scratch folder and compiled with no unit hint, as a studio's export would arrive.
#include "import/bvh.hpp"
#include "library_build/library_source.hpp"
#include "support/bvh_variants.hpp"
#include "support/test_paths.hpp"

#include <gtest/gtest.h>

#include <string>

namespace foresight::test {

/// Fails the calling test (use ASSERT_NO_FATAL_FAILURE) when the take or the library does not load.
inline void foreign_walk_library(const std::string& rotation_order, MotionLibrary& lib) {
  BvhDocument take;
  std::string error;
  ASSERT_TRUE(bvh_load(mocap_dir() / "locomotion" / "bandai_dataset-1_walk_normal_001.bvh", take, error)) << error;
  scale_document(take, 1.0f / 2.54f);
  insert_parent(take, 0, "Reference", 0.0f);
  if (!rotation_order.empty()) reorder_rotations(take, rotation_order);
  const auto dir = scratch_dir();
  ASSERT_TRUE(bvh_save(dir / "walk_variant.bvh", take, error)) << error;
  MotionSource source;
  source.motions_dir = dir;
  ASSERT_TRUE(motion_library_from_folder(source, lib, nullptr, error)) << error;
}

}  // namespace foresight::test

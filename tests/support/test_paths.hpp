#pragma once
// Where tests find real data: the mocap folder beside the repository, and a scratch folder.
#include <filesystem>

namespace foresight::test {

/// ../shared/mocap (absent on some machines: tests that need it GTEST_SKIP with a message).
std::filesystem::path mocap_dir();
/// A fresh, empty scratch folder for this test (created under the build tree).
std::filesystem::path scratch_dir();
/// The repository (for files it ships, such as deploy/).
std::filesystem::path source_dir();

}  // namespace foresight::test

/// Skips the current test with a message when ../shared/mocap is not there.
#define FORESIGHT_REQUIRE_MOCAP()                                                      \
  do {                                                                                 \
    if (!std::filesystem::is_directory(::foresight::test::mocap_dir()))                \
      GTEST_SKIP() << "mocap folder absent: " << ::foresight::test::mocap_dir();       \
  } while (0)

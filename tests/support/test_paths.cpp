#include "support/test_paths.hpp"

#include <gtest/gtest.h>

namespace foresight::test {

std::filesystem::path mocap_dir() {
  if (const char* env = std::getenv("FORESIGHT_MOCAP_DIR")) return env;
  return FORESIGHT_MOCAP_DIR;
}

std::filesystem::path source_dir() { return FORESIGHT_SOURCE_DIR; }

std::filesystem::path scratch_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::filesystem::path dir = std::filesystem::path(FORESIGHT_TEST_TMP) /
                              (std::string(info->test_suite_name()) + "." + info->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace foresight::test

#pragma once
// Shared by the adaptation tests: the default cast (fighter_build/fighter_cast.hpp), its limb models
// expected to build.
#include "fighter_build/fighter_cast.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace foresight::test {

struct FighterCast : foresight::FighterCast {
  FighterCast() { EXPECT_TRUE(error.empty()) << error; }
};

inline bool finite(vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace foresight::test

#include <gtest/gtest.h>
// Replaced by the real tests of shared/library as they land.
TEST(Placeholder_library, Builds) { SUCCEED(); }

#include <gtest/gtest.h>
// Replaced by the real tests of shared/author as they land.
TEST(Placeholder_author, Builds) { SUCCEED(); }

// LogHistogram: percentiles within one bin (2 %) of the exact ones, merging equals adding.
#include "transport/histogram.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace foresight::protocol {
namespace {

TEST(LogHistogram, EmptyIsZero) {
  LogHistogram h;
  EXPECT_EQ(h.count(), 0u);
  EXPECT_EQ(h.percentile(0.5), 0.0);
  EXPECT_EQ(h.mean(), 0.0);
}

TEST(LogHistogram, PercentilesWithinTwoPercent) {
  std::mt19937_64 rng(7);
  std::lognormal_distribution<double> dist(1.0, 1.0);
  std::vector<double> values;
  LogHistogram h;
  for (int i = 0; i < 100000; ++i) {
    values.push_back(dist(rng));
    h.add(values.back());
  }
  std::sort(values.begin(), values.end());
  for (double q : {0.01, 0.5, 0.9, 0.99, 0.999}) {
    const double exact = values[static_cast<size_t>(std::ceil(q * values.size())) - 1];
    EXPECT_NEAR(h.percentile(q), exact, exact * 0.02) << q;
  }
  EXPECT_DOUBLE_EQ(h.percentile(0.0), values.front());
  EXPECT_DOUBLE_EQ(h.percentile(1.0), values.back());
  EXPECT_DOUBLE_EQ(h.max(), values.back());
}

TEST(LogHistogram, MergeEqualsAddingEverything) {
  LogHistogram a, b, all;
  for (int i = 1; i <= 1000; ++i) {
    const double v = 0.01 * i;
    (i % 3 ? a : b).add(v);
    all.add(v);
  }
  a.merge(b);
  EXPECT_EQ(a.count(), all.count());
  EXPECT_DOUBLE_EQ(a.mean(), all.mean());
  for (double q : {0.1, 0.5, 0.99}) EXPECT_DOUBLE_EQ(a.percentile(q), all.percentile(q));
}

TEST(LogHistogram, ExtremesAndNonFiniteValues) {
  LogHistogram h;
  h.add(0.0);
  h.add(-3.0);
  h.add(1e12);
  h.add(std::nan(""));
  h.add(INFINITY);
  EXPECT_EQ(h.count(), 3u);
  EXPECT_EQ(h.min(), -3.0);
  EXPECT_EQ(h.max(), 1e12);
  EXPECT_LE(h.percentile(0.5), 0.0);
}

}  // namespace
}  // namespace foresight::protocol

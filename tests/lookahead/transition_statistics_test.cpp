#include "lookahead/transition_statistics.hpp"

#include <gtest/gtest.h>

namespace foresight {
namespace {

TEST(TransitionStatistics, FrequenciesBecomeSmoothedPerParentProbabilities) {
  MotionGraph g;
  for (int i = 0; i < 3; ++i) g.segments.push_back({"s" + std::to_string(i), 0, 0, 1, kTagNone});
  g.transitions = {{0, 1, 0}, {0, 2, 0}, {1, 0, 0}, {2, 0, 0}};
  g.finalize();
  // 0 -> 1 taken three times, 0 -> 2 once; bad indices are ignored.
  const int taken[] = {0, 0, 0, 1, -5, 99};
  const TransitionStatistics s = transition_statistics_learn(g, taken, 0.5f);
  ASSERT_EQ(s.probability.size(), 4u);
  EXPECT_NEAR(s.probability[0], 3.5f / 5.0f, 1e-6f);
  EXPECT_NEAR(s.probability[1], 1.5f / 5.0f, 1e-6f);
  // Only child: certain, seen or not.
  EXPECT_NEAR(s.probability[2], 1.0f, 1e-6f);
  EXPECT_NEAR(s.probability[3], 1.0f, 1e-6f);
  // Without smoothing an unseen child gets zero.
  EXPECT_EQ(transition_statistics_learn(g, taken, 0.0f).probability[1], 0.25f);
  EXPECT_EQ(transition_statistics_learn(g, {}, 0.0f).probability[0], 0.0f);
}

}  // namespace
}  // namespace foresight

// retrieve() must not allocate once the retriever exists (it runs in the server tick). Counted by
// the test binary's replaced global operator new (support/alloc_counter).
#include "fighter/retrieval.hpp"
#include "fighter_build/retrieval_index.hpp"
#include "fighter_build/fighter_database_build.hpp"

#include "support/alloc_counter.hpp"

#include <gtest/gtest.h>

namespace {
// Volatile so the compiler cannot elide the probe's new/delete pair.
int* volatile g_probe = nullptr;
}  // namespace

namespace foresight {
namespace {

TEST(RetrievalAllocation, RetrieveAllocatesNothing) {
  FighterDatabase db;
  std::string error;
  ASSERT_TRUE(fighter_database_add_default_library(db, error)) << error;
  const FighterDatabase big = fighter_database_synthetic(db, 300, 5);
  FighterRetrievalIndex index;
  fighter_retrieval_prepare(big, PoseClusterParams{}, RetrievalIndexParams{}, {}, index, nullptr, nullptr);
  FighterRetriever retriever(index);
  RetrievalQuery q;
  const FighterEntry& e = db.entries[0];
  for (int i = 0; i < kPoseKeyPoints; ++i)
    q.pose_key_points_m[static_cast<std::size_t>(i)] = e.key_points[static_cast<std::size_t>(i)] * e.body_size_m;
  q.body_size_m = e.body_size_m;
  RetrievalResult r;
  // The check itself must be able to fail: an allocation while counting is seen.
  {
    test::AllocationCount probe;
    g_probe = new int(3);
    ASSERT_EQ(probe.allocations(), 1);
  }
  delete g_probe;

  int found = 0;
  test::AllocationCount count;
  for (int i = 0; i < 200; ++i) {
    q.target_m = vec3(0.01f * static_cast<float>(i % 40) - 0.2f, 0.5f + 0.006f * static_cast<float>(i), 0.4f + 0.5f * static_cast<float>(i % 7) / 7.0f);
    q.kind = i % 3 == 0 ? std::nullopt : std::optional<StrikeKind>(i % 3 == 1 ? StrikeKind::kPunch : StrikeKind::kKick);
    q.side = i % 5 == 0 ? std::optional<StrikeSide>(StrikeSide::kLeft) : std::nullopt;
    found += retriever.retrieve(q, RetrievalParams{}, r) ? 1 : 0;
  }
  EXPECT_EQ(found, 200);
  EXPECT_EQ(count.allocations(), 0);
}

}  // namespace
}  // namespace foresight

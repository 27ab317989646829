// Motion retrieval (retrieval.hpp, paper 3.3) on the default library's strikes.
#include "fighter/retrieval.hpp"
#include "fighter_build/retrieval_index.hpp"
#include "fighter_build/fighter_database_build.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace foresight {
namespace {

struct Fixture {
  FighterDatabase db;
  FighterRetrievalIndex index;
  explicit Fixture(int k = 0) {
    std::string error;
    EXPECT_TRUE(fighter_database_add_default_library(db, error)) << error;
    PoseClusterParams params;
    params.k = k;
    fighter_retrieval_prepare(db, params, RetrievalIndexParams{}, {}, index, nullptr, nullptr);
  }
  /// The fighter in its guard stance (the first pose of every default strike), metres.
  RetrievalQuery stance_query(vec3 target_m) const {
    RetrievalQuery q;
    const FighterEntry& e = db.entries[0];
    for (int i = 0; i < kPoseKeyPoints; ++i)
      q.pose_key_points_m[static_cast<std::size_t>(i)] = e.key_points[static_cast<std::size_t>(i)] * e.body_size_m;
    q.body_size_m = e.body_size_m;
    q.target_m = target_m;
    return q;
  }
  const FighterEntry& entry(const RetrievalResult& r) const { return db.entries[static_cast<std::size_t>(r.entry)]; }
};

void expect_finite(const RetrievalResult& r) {
  EXPECT_TRUE(std::isfinite(r.cost));
  EXPECT_TRUE(std::isfinite(r.pose_distance));
  EXPECT_TRUE(std::isfinite(r.target_distance));
  EXPECT_TRUE(std::isfinite(r.alignment.heading_rad));
  EXPECT_TRUE(std::isfinite(r.alignment.pos_m.x) && std::isfinite(r.alignment.pos_m.y));
}

TEST(Retrieval, PicksAHighKickForAHighTargetAndALowPunchForALowOne) {
  Fixture f;
  FighterRetriever retriever(f.index);
  RetrievalResult r;

  RetrievalQuery q = f.stance_query(vec3(0.0f, 1.55f, 0.6f));  // head height, a stride ahead
  q.kind = StrikeKind::kKick;
  ASSERT_TRUE(retriever.retrieve(q, RetrievalParams{}, r));
  EXPECT_EQ(f.entry(r).kind, StrikeKind::kKick) << f.entry(r).name;
  EXPECT_EQ(f.entry(r).height, StrikeHeight::kHigh) << f.entry(r).name;
  EXPECT_EQ(r.scope, RetrievalScope::kCluster);

  q = f.stance_query(vec3(0.0f, 0.75f, 0.55f));  // belly height, close
  q.kind = StrikeKind::kPunch;
  ASSERT_TRUE(retriever.retrieve(q, RetrievalParams{}, r));
  EXPECT_EQ(f.entry(r).kind, StrikeKind::kPunch) << f.entry(r).name;
  EXPECT_EQ(f.entry(r).height, StrikeHeight::kLow) << f.entry(r).name;
  EXPECT_LT(r.start_frame, r.hit_frame);
  expect_finite(r);
}

TEST(Retrieval, WithoutAnOrderTheTargetHeightDecides) {
  Fixture f;
  FighterRetriever retriever(f.index);
  RetrievalResult r;
  ASSERT_TRUE(retriever.retrieve(f.stance_query(vec3(0.0f, 1.53f, 0.75f)), RetrievalParams{}, r));
  EXPECT_EQ(f.entry(r).height, StrikeHeight::kHigh) << f.entry(r).name;
  ASSERT_TRUE(retriever.retrieve(f.stance_query(vec3(0.0f, 0.62f, 0.9f)), RetrievalParams{}, r));
  EXPECT_EQ(f.entry(r).height, StrikeHeight::kLow) << f.entry(r).name;
}

TEST(Retrieval, ObeysTheOrderedKindAndSide) {
  Fixture f;
  FighterRetriever retriever(f.index);
  RetrievalResult r;
  for (StrikeKind kind : {StrikeKind::kPunch, StrikeKind::kKick})
    for (StrikeSide side : {StrikeSide::kLeft, StrikeSide::kRight})
      for (vec3 target : {vec3(0.3f, 1.5f, 0.6f), vec3(-0.3f, 0.7f, 0.7f), vec3(0.0f, 1.1f, 0.65f)}) {
        RetrievalQuery q = f.stance_query(target);
        q.kind = kind;
        q.side = side;
        ASSERT_TRUE(retriever.retrieve(q, RetrievalParams{}, r));
        EXPECT_EQ(f.entry(r).kind, kind);
        EXPECT_EQ(f.entry(r).side, side);
        expect_finite(r);
      }
}

TEST(Retrieval, FindsEachStrikeFromItsOwnStartAndHitPoint) {
  Fixture f;
  FighterRetriever retriever(f.index);
  RetrievalResult r;
  for (const FighterEntry& e : f.db.entries) {
    RetrievalQuery q = f.stance_query(e.hit_point_m());
    q.kind = e.kind;
    q.side = e.side;
    ASSERT_TRUE(retriever.retrieve(q, RetrievalParams{}, r)) << e.name;
    // The strike itself (or one landing as close) is chosen: within 2 cm of the target.
    EXPECT_LT(r.target_distance * q.body_size_m, 0.02f) << e.name << " -> " << f.entry(r).name;
    EXPECT_EQ(f.entry(r).height, e.height) << e.name << " -> " << f.entry(r).name;
  }
}

TEST(Retrieval, AShiftedRootFrameIsAlignedAway) {
  // The same pose and target expressed from a root frame turned by 20 degrees and moved: the same
  // strike and start, and the alignment carries the entry onto the moved pose.
  Fixture f;
  FighterRetriever retriever(f.index);
  RetrievalQuery q = f.stance_query(vec3(0.1f, 1.15f, 0.6f));
  q.kind = StrikeKind::kPunch;
  RetrievalResult plain, moved;
  ASSERT_TRUE(retriever.retrieve(q, RetrievalParams{}, plain));
  const Placement shift{vec2(0.2f, -0.1f), radians(20.0f)};
  for (vec3& p : q.pose_key_points_m) p = shift.apply(p);
  q.target_m = shift.apply(q.target_m);
  ASSERT_TRUE(retriever.retrieve(q, RetrievalParams{}, moved));
  EXPECT_EQ(moved.entry, plain.entry);
  EXPECT_EQ(moved.start_frame, plain.start_frame);
  EXPECT_NEAR(moved.target_distance, plain.target_distance, 1e-3f);
  EXPECT_NEAR(wrap_angle(moved.alignment.heading_rad - plain.alignment.heading_rad - shift.heading_rad), 0.0f, 1e-3f);
  const Placement expected = shift.compose(plain.alignment);
  EXPECT_NEAR(glm::length(moved.alignment.pos_m - expected.pos_m), 0.0f, 1e-3f);
}

TEST(Retrieval, ScalesTheTargetByBodySize) {
  // Paper eq. 1: a fighter 1.3 times the actor's size, with a target 1.3 times as far, is the
  // same problem; the same target for the smaller fighter is not.
  Fixture f;
  FighterRetriever retriever(f.index);
  RetrievalQuery q = f.stance_query(vec3(0.0f, 1.5f, 0.6f));
  q.kind = StrikeKind::kKick;
  RetrievalResult base, big;
  ASSERT_TRUE(retriever.retrieve(q, RetrievalParams{}, base));
  for (vec3& p : q.pose_key_points_m) p *= 1.3f;
  q.body_size_m *= 1.3f;
  q.target_m *= 1.3f;
  ASSERT_TRUE(retriever.retrieve(q, RetrievalParams{}, big));
  EXPECT_EQ(big.entry, base.entry);
  EXPECT_EQ(big.start_frame, base.start_frame);
  EXPECT_NEAR(big.target_distance, base.target_distance, 1e-4f);
  EXPECT_NEAR(big.target_in_entry_m.y, base.target_in_entry_m.y, 1e-3f);  // actor metres either way
}

TEST(Retrieval, AnUnreachableTargetFallsBackWithoutNaN) {
  Fixture f;
  FighterRetriever retriever(f.index);
  RetrievalResult r;
  for (vec3 target : {vec3(0.0f, 1.0f, 8.0f), vec3(0.0f, -3.0f, 0.0f), vec3(5.0f, 9.0f, -5.0f)}) {
    RetrievalQuery q = f.stance_query(target);
    q.kind = StrikeKind::kKick;
    ASSERT_TRUE(retriever.retrieve(q, RetrievalParams{}, r));
    EXPECT_EQ(r.scope, RetrievalScope::kNoBoxFilter);
    EXPECT_GE(r.candidates_scored, 1);
    EXPECT_EQ(f.entry(r).kind, StrikeKind::kKick);
    expect_finite(r);
  }
}

TEST(Retrieval, WidensPastAClusterWithoutTheOrderedKind) {
  // With many clusters, the pose of a kick at full extension has a cluster of kick poses only;
  // an ordered punch must come from further clusters, and the result says so.
  Fixture f(40);
  FighterRetriever retriever(f.index);
  const FighterEntry& kick = f.db.entries[13];  // kick_right_front_mid
  ASSERT_EQ(kick.kind, StrikeKind::kKick);
  RetrievalQuery q;
  const int hit = kick.hit_frame - kick.start_frame;
  for (int i = 0; i < kPoseKeyPoints; ++i)
    q.pose_key_points_m[static_cast<std::size_t>(i)] =
        kick.key_points[static_cast<std::size_t>(hit * kPoseKeyPoints + i)] * kick.body_size_m;
  q.body_size_m = kick.body_size_m;
  q.target_m = vec3(0.0f, 1.2f, 0.6f);
  q.kind = StrikeKind::kPunch;
  RetrievalResult r;
  ASSERT_TRUE(retriever.retrieve(q, RetrievalParams{}, r));
  EXPECT_EQ(f.entry(r).kind, StrikeKind::kPunch);
  EXPECT_NE(r.scope, RetrievalScope::kCluster) << retrieval_scope_name(r.scope);
  EXPECT_FALSE(r.capped);

  // With a budget of one cluster the search does not widen: it says so, and still answers.
  RetrievalParams budget;
  budget.max_clusters = 1;
  ASSERT_TRUE(retriever.retrieve(q, budget, r));
  EXPECT_EQ(f.entry(r).kind, StrikeKind::kPunch);
  EXPECT_EQ(r.scope, RetrievalScope::kNoBoxFilter);
  EXPECT_TRUE(r.capped);
  EXPECT_LE(r.clusters_searched, 1);
}

TEST(Retrieval, NothingOfTheOrderedKindIsAnEmptyAnswer) {
  Fixture f;
  FighterDatabase punches;
  punches.takes = f.db.takes;
  for (const FighterEntry& e : f.db.entries)
    if (e.kind == StrikeKind::kPunch) punches.entries.push_back(e);
  FighterRetrievalIndex index;
  fighter_retrieval_prepare(punches, PoseClusterParams{}, RetrievalIndexParams{}, {}, index, nullptr, nullptr);
  FighterRetriever retriever(index);
  RetrievalQuery q = f.stance_query(vec3(0.0f, 1.0f, 0.7f));
  q.kind = StrikeKind::kKick;
  RetrievalResult r;
  EXPECT_FALSE(retriever.retrieve(q, RetrievalParams{}, r));
  EXPECT_FALSE(r.found());
  q.kind = StrikeKind::kPunch;
  EXPECT_TRUE(retriever.retrieve(q, RetrievalParams{}, r));
}

TEST(Retrieval, PoseWeightPrefersTheClosestStartPose) {
  // With the target ignored, the chosen start pose is the fighter's own pose (distance ~ 0).
  Fixture f;
  FighterRetriever retriever(f.index);
  RetrievalParams params;
  params.w_target = 0.0f;
  RetrievalResult r;
  ASSERT_TRUE(retriever.retrieve(f.stance_query(vec3(0.0f, 1.2f, 0.6f)), params, r));
  EXPECT_LT(r.pose_distance, 1e-3f);
  EXPECT_EQ(r.start_frame, f.entry(r).start_frame);
}

}  // namespace
}  // namespace foresight

namespace foresight {
namespace {

TEST(Retrieval, RefusesABodySizeThatIsNotPositive) {
  Fixture f;
  FighterRetriever retriever(f.index);
  RetrievalQuery q = f.stance_query(vec3(0.0f, 1.2f, 0.6f));
  RetrievalResult r;
  for (float size : {0.0f, -1.0f, std::nanf("")}) {
    q.body_size_m = size;
    EXPECT_FALSE(retriever.retrieve(q, RetrievalParams{}, r)) << size;
    EXPECT_FALSE(r.found());
  }
}

}  // namespace
}  // namespace foresight

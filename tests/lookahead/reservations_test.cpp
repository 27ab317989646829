// Reservations (lookahead/reservations.hpp) answer exactly what comparing every frame of the
// candidate segment with every frame anyone else reserved would: the runs, boxes and disc tests
// are shortcuts, never a different answer. Checked on crowds of random reservations, on the
// built-in library and on capture the team did not make, inside the scene and past its edges.
#include "lookahead/reservations.hpp"

#include "library/foreign_capture.hpp"
#include "lookahead_fixture.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace foresight {
namespace {

constexpr float kClearance_m = 0.05f;

struct Reservation {
  int owner;
  int segment;
  int from_frame;
  Placement start;
};

// The reference: every placed frame of the candidate against every placed frame of every other
// owner's reservation.
bool blocks_by_every_pair(const MotionLibrary& lib, const std::vector<Reservation>& reserved, int self,
                          int segment, const Placement& start) {
  for (const BodyVolume& mine : lib.volumes(segment)) {
    const BodyVolume v = place(mine, start);
    for (const Reservation& r : reserved) {
      if (r.owner == self) continue;
      const auto frames = lib.volumes(r.segment);
      for (size_t f = static_cast<size_t>(r.from_frame); f < frames.size(); ++f)
        if (footprints_overlap(v, place(frames[f], r.start), kClearance_m)) return true;
    }
  }
  return false;
}

struct Counts {
  int blocked = 0;
  int free = 0;
};

// `owners` avatars with one or two reservations each (a steered avatar reserves again) spread
// over `area` (which pokes past the grid's bounds by a metre), then `queries` random questions.
Counts expect_same_answers_as_every_pair(const MotionLibrary& lib, int owners, float area_m, int queries,
                                         unsigned seed) {
  const GroundRect bounds{vec2(0.0f), vec2(area_m - 2.0f)};
  Reservations reservations;
  reservations.configure(bounds, 1.0f, kClearance_m);
  std::mt19937 rng(seed);
  const int segments = static_cast<int>(lib.segment_shapes.size());
  std::uniform_int_distribution<int> any_segment(0, segments - 1);
  std::uniform_real_distribution<float> coordinate(-1.0f, area_m - 1.0f), heading(-kPi, kPi);
  const auto random_placement = [&] { return Placement{vec2(coordinate(rng), coordinate(rng)), heading(rng)}; };
  std::vector<Reservation> reserved;
  for (int owner = 0; owner < owners; ++owner) {
    const int runs = 1 + owner % 2;
    for (int k = 0; k < runs; ++k) {
      const int segment = any_segment(rng);
      const int frames = static_cast<int>(lib.volumes(segment).size());
      const int from = std::uniform_int_distribution<int>(0, frames)(rng);  // == frames: nothing left
      reserved.push_back({owner, segment, from, random_placement()});
      reservations.add(owner, lib, segment, from, reserved.back().start);
    }
  }
  Counts counts;
  for (int q = 0; q < queries; ++q) {
    const int self = std::uniform_int_distribution<int>(-1, owners - 1)(rng);
    const int segment = any_segment(rng);
    const Placement start = random_placement();
    const bool want = blocks_by_every_pair(lib, reserved, self, segment, start);
    EXPECT_EQ(reservations.blocks(self, lib, segment, start), want)
        << "query " << q << ": self " << self << ", segment " << segment << " at (" << start.pos_m.x << ", "
        << start.pos_m.y << ") heading " << start.heading_rad;
    ++(want ? counts.blocked : counts.free);
  }
  reservations.clear();
  for (int q = 0; q < 20; ++q)
    EXPECT_FALSE(reservations.blocks(-1, lib, any_segment(rng), random_placement())) << "cleared: nothing reserved";
  return counts;
}

void expect_exact_in_crowds(const MotionLibrary& lib) {
  // A crowd (40 avatars on 8 x 8 m: most questions blocked) and a sparse field (60 on 30 x 30 m).
  const Counts crowd = expect_same_answers_as_every_pair(lib, 40, 8.0f, 400, 1);
  const Counts field = expect_same_answers_as_every_pair(lib, 60, 30.0f, 600, 2);
  // Both answers occur often in each, or the comparison above proves little.
  EXPECT_GT(crowd.blocked, 100);
  EXPECT_GT(crowd.free, 10);
  EXPECT_GT(field.blocked, 30);
  EXPECT_GT(field.free, 100);
}

TEST(Reservations, AnswerAsComparingEveryPairOfFramesWould) {
  ASSERT_NO_FATAL_FAILURE(expect_exact_in_crowds(test::default_library()));
}

// Capture the team did not make: the Bandai walk in inches under a dummy root, its own segments
// and body volumes.
TEST(Reservations, AnswerAsComparingEveryPairOfFramesWouldOnAForeignCapture) {
  FORESIGHT_REQUIRE_MOCAP();
  MotionLibrary lib;
  ASSERT_NO_FATAL_FAILURE(test::foreign_walk_library("", lib));
  ASSERT_NO_FATAL_FAILURE(expect_exact_in_crowds(lib));
}

// An avatar is never blocked by its own reservations, however many, and is by anyone else's at
// the same place.
TEST(Reservations, OwnReservationsNeverBlock) {
  const MotionLibrary& lib = test::default_library();
  Reservations reservations;
  reservations.configure(GroundRect{vec2(0.0f), vec2(10.0f)});
  const Placement here{vec2(5.0f), 0.3f};
  for (int k = 0; k < 3; ++k) reservations.add(7, lib, 0, 0, here);
  EXPECT_FALSE(reservations.blocks(7, lib, 0, here));
  EXPECT_TRUE(reservations.blocks(8, lib, 0, here));
  EXPECT_TRUE(reservations.blocks(-1, lib, 0, here));
}

}  // namespace
}  // namespace foresight
